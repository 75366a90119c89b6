#!/usr/bin/env bash
# Creates .venv with Python 3.12 and installs the project (idempotent; re-runs only when
# pyproject.toml changes). Sourced by scripts/main.sh and scripts/test.sh.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VENV="$ROOT/.venv"

find_python312() {
  if command -v python3.12 >/dev/null 2>&1 && python3.12 -c 'import sys; assert sys.version_info[:2] == (3, 12)' 2>/dev/null; then
    command -v python3.12; return
  fi
  if command -v pyenv >/dev/null 2>&1; then
    local v; v="$(pyenv versions --bare 2>/dev/null | grep -E '^3\.12(\.|$)' | tail -1 || true)"
    if [ -n "$v" ]; then echo "$(pyenv root)/versions/$v/bin/python3.12"; return; fi
  fi
  echo "error: Python 3.12 not found (lerobot 0.6 needs it). Install it, e.g. 'pyenv install 3.12', and re-run." >&2
  exit 1
}

ensure_system_libs() {
  # Headless rendering needs EGL (Mesa llvmpipe on CPU) or OSMesa; LeRobot's default video decoder
  # (torchcodec) needs FFmpeg's shared libraries.
  local pkgs=()
  if ! ldconfig -p | grep -q 'libEGL.so.1' || ! ldconfig -p | grep -q 'libOSMesa'; then
    pkgs+=(libegl1 libgl1-mesa-dri libosmesa6)
  fi
  if ! ldconfig -p | grep -q 'libavcodec.so' || ! ldconfig -p | grep -q 'libavdevice.so'; then
    pkgs+=(libavcodec59 libavformat59 libavutil57 libswscale6 libswresample4 libavdevice59 libavfilter8)
  fi
  # The tests open report.html in headless Chromium (scripts/test.sh sets ACTIVEARENA_TEST_BROWSER=1).
  if [ "${ACTIVEARENA_TEST_BROWSER:-0}" = "1" ] && ! { command -v chromium && command -v chromedriver; } >/dev/null 2>&1; then
    pkgs+=(chromium chromium-driver)
  fi
  [ "${#pkgs[@]}" -eq 0 ] && return
  if [ "$(id -u)" = "0" ] && command -v apt-get >/dev/null 2>&1; then
    echo "[bootstrap] installing ${pkgs[*]} with apt-get" >&2
    apt-get update -qq >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${pkgs[@]}" >/dev/null
  else
    echo "[bootstrap] warning: missing system libraries; install ${pkgs[*]}" >&2
  fi
}

ensure_system_libs
STAMP="$VENV/.installed-$(sha256sum "$ROOT/pyproject.toml" | cut -c1-16)"
if [ ! -f "$STAMP" ]; then
  if [ ! -x "$VENV/bin/python" ]; then
    PY="$(find_python312)"
    echo "[bootstrap] creating $VENV with $PY" >&2
    "$PY" -m venv "$VENV"
  fi
  echo "[bootstrap] installing lerobot_activearena and its dependencies (first run: several minutes)" >&2
  "$VENV/bin/python" -m pip install -q --upgrade pip >/dev/null
  "$VENV/bin/python" -m pip install -q -e "$ROOT[test]"
  # the remote-policy tests serve policies with openpi's own server; its packages pin numpy < 2, which
  # LeRobot cannot use, and the server needs only msgpack and websockets: installed without dependencies
  "$VENV/bin/python" -m pip install -q --no-deps openpi-client==0.1.2 openpi-server==0.1.0
  rm -f "$VENV"/.installed-*
  touch "$STAMP"
fi
export PATH="$VENV/bin:$PATH"
export MUJOCO_GL="${MUJOCO_GL:-egl}"
