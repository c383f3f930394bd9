#!/usr/bin/env bash
# Installs the Blender add-on ICM Unwrap (python/blender/icm_unwrap) and the Python module icm
# it calls into Blender's user scripts, and enables the add-on (doc/blender.md):
#   SCRIPTS/addons/icm_unwrap   the add-on (Blender loads add-ons from SCRIPTS/addons)
#   SCRIPTS/addons/modules/icm  the package icm with its compiled _icm (SCRIPTS/addons/modules is
#                               on the sys.path of Blender's Python, for the modules of add-ons)
# SCRIPTS is $BLENDER_USER_SCRIPTS if set, else ~/.config/blender/X.Y/scripts for the installed
# Blender X.Y (what bpy.utils.user_resource('SCRIPTS') gives). The module is the one of
# BUILD_DIR (default build/), built here (target _icm) if it is not yet: Debian's Blender runs on
# the system's Python 3.11, the /usr/bin/python3 the module is built for.
#   bash scripts/install_blender_addon.sh [--no-enable] [BUILD_DIR]
# --no-enable copies the files only (the add-on is then enabled in Preferences > Add-ons, or
# per run with `blender --addons icm_unwrap`).
set -euo pipefail
cd "$(dirname "$0")/.."
enable=1
if [ "${1:-}" = "--no-enable" ]; then
  enable=0
  shift
fi
build="${1:-build}"
command -v blender >/dev/null || { echo "install_blender_addon: no blender (apt-get install blender)" >&2; exit 1; }

if ! compgen -G "$build/python/icm/_icm*.so" >/dev/null; then
  [ -f "$build/CMakeCache.txt" ] || cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release
  cmake --build "$build" --target _icm -j"${ICM_JOBS:-2}"
fi

if [ -n "${BLENDER_USER_SCRIPTS:-}" ]; then
  scripts="$BLENDER_USER_SCRIPTS"
else
  version="$(blender --version 2>/dev/null | sed -n 's/^Blender \([0-9]*\.[0-9]*\).*/\1/p' | head -n 1)"
  [ -n "$version" ] || { echo "install_blender_addon: cannot tell Blender's version" >&2; exit 1; }
  scripts="$HOME/.config/blender/$version/scripts"
fi

mkdir -p "$scripts/addons/modules"
rm -rf "$scripts/addons/icm_unwrap" "$scripts/addons/modules/icm"
cp -r python/blender/icm_unwrap "$scripts/addons/icm_unwrap"
rm -rf "$scripts/addons/icm_unwrap/__pycache__"
mkdir -p "$scripts/addons/modules/icm"
cp "$build"/python/icm/*.py "$build"/python/icm/py.typed "$build"/python/icm/_icm*.so "$scripts/addons/modules/icm/"
echo "installed: $scripts/addons/icm_unwrap and $scripts/addons/modules/icm"

if [ "$enable" = 1 ]; then
  BLENDER_USER_SCRIPTS="$scripts" blender -b --python-exit-code 1 --python-expr \
    "import bpy; bpy.ops.preferences.addon_enable(module='icm_unwrap'); bpy.ops.wm.save_userpref()" \
    >/dev/null
  echo "enabled: ICM Unwrap (3D Viewport, edit mode: UV > ICM Unwrap)"
fi
