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
  libeigen3-dev libceres-dev libopencv-dev
  libspdlog-dev libcli11-dev libyaml-cpp-dev libgtest-dev libssl-dev nlohmann-json3-dev libnanoflann-dev
  iproute2 procps
  librosbag-storage-dev libsensor-msgs-dev libnav-msgs-dev libtf2-msgs-dev
  pluginlib-dev librcpputils-dev libament-index-cpp-dev libpcl-dev
  python3-rosbag python3-sensor-msgs python3-nav-msgs python3-tf2-msgs python3-geometry-msgs
  libcivetweb-dev nodejs chromium firefox-esr xvfb
)
# libcivetweb-dev: slide-viewer's HTTP and WebSocket server; nodejs (and npm, below): the viewer
# page's three.js and puppeteer-core, which drives chromium (the demo's pictures, a browser test)
# and firefox-esr (a browser test; in a window on xvfb, as headless Firefox has no WebGL).

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

# The viewer page's npm packages (daemons/viewer/web/package-lock.json: three, and puppeteer-core
# for its pictures and browser tests), installed when missing or older than the lock file. Debian's nodejs
# comes without npm, which is a package of its own (other nodejs builds bring it).
install_web_packages() {
  local web="$SLIDE_ROOT/daemons/viewer/web"
  [[ -f "$web/node_modules/.package-lock.json" && "$web/node_modules/.package-lock.json" -nt "$web/package-lock.json" ]] && return 0
  if ! command -v npm > /dev/null; then
    local sudo=""
    [[ $(id -u) -eq 0 ]] || sudo="sudo"
    log "installing npm (Debian package) for the viewer page's three.js"
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends npm > /dev/null
  fi
  log "installing the viewer page's npm packages in $web"
  (cd "$web" && npm ci --no-audit --no-fund --loglevel=error > /dev/null) || die "npm ci in $web failed"
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
  install_web_packages
  build_project
}
