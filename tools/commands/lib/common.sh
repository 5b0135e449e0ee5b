# Shared helpers for ./slide commands (sourced, never run).

log() { printf '\033[1m[slide]\033[0m %s\n' "$*" >&2; }
die() { printf 'slide: %s\n' "$*" >&2; exit 1; }

# wants_help "$@": true when the arguments ask for --help/-h.
wants_help() {
  local a
  for a in "$@"; do [[ "$a" == "--help" || "$a" == "-h" ]] && return 0; done
  return 1
}

# Debian packages the project builds and runs with.
SLIDE_PACKAGES=(
  build-essential cmake pkg-config git
  liblcm-dev liblcm-bin liblcm-java default-jdk-headless libglib2.0-dev
  libeigen3-dev libceres-dev libopencv-dev libpcl-dev
  libspdlog-dev libcli11-dev libyaml-cpp-dev libgtest-dev libssl-dev
  iproute2 procps
)

missing_packages() {
  local p status
  for p in "${SLIDE_PACKAGES[@]}"; do
    status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
    [[ "$status" == "install ok installed" ]] || echo "$p"
  done
}

install_packages() {
  local missing
  mapfile -t missing < <(missing_packages)
  [[ ${#missing[@]} -eq 0 ]] && return 0
  local sudo=""
  [[ $(id -u) -eq 0 ]] || sudo="sudo"
  log "installing ${#missing[@]} Debian packages: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

build_project() {
  if [[ ! -f "$SLIDE_BUILD/CMakeCache.txt" ]]; then
    cmake -S "$SLIDE_ROOT" -B "$SLIDE_BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
  fi
  cmake --build "$SLIDE_BUILD" -j "$(nproc)" -- --no-print-directory
}

# ensure_built: install what is missing and bring the build up to date (cheap when current).
ensure_built() {
  install_packages
  build_project
}
