# help: install Debian dependencies (only what is missing) and build (Release, all cores)
main() {
  if wants_help "$@"; then
    cat <<USAGE
usage: ./slide setup
Installs the Debian packages the project needs (apt-get update runs only when one is
missing; quiet when all are present), then configures and builds into build/ (Release,
$(nproc) jobs). Set SLIDE_BUILD to build elsewhere.
USAGE
    return 0
  fi
  [[ $# -eq 0 ]] || die "setup takes no arguments (got: $*)"
  ensure_built
  log "built into $SLIDE_BUILD"
}
