#!/usr/bin/env bash
# Regenerates the pictures of docs/user-guide.md (docs/img/gui_*.png) with `facehex-gui --screenshot`, each state on
# a virtual 1920 x 1080 screen, and the window on a laptop's 1366 x 768 screen (gui_laptop.png), as the application
# opens on each: sized from the screen, not from a saved session.
#
# Usage, from anywhere in the repository, after a build of facehex-gui:
#   scripts/regenerate-gui-images.sh [STATE...]   (default: every state the guide shows, and the laptop picture)
#   FACEHEX_GUI=path/to/facehex-gui overrides build/bin/facehex-gui.
# Needs xvfb-run. Each state opens the bundled demo (the bundled CT for ct and segmentation) and computes what it
# shows, so the transfer states take as long as a transfer.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
gui=${FACEHEX_GUI:-build/bin/facehex-gui}
if [ ! -x "$gui" ]; then
  echo "regenerate-gui-images.sh: no $gui; build it first: cmake --build build --target facehex-gui" >&2
  exit 1
fi
states=("$@")
[ ${#states[@]} -gt 0 ] || states=(ct segmentation loaded plane landmarks fields glyphs transfer quality messages laptop)

shot() {  # shot SCREEN FILE STATE
  xvfb-run -a -s "-screen 0 $1x24" env QT_QPA_PLATFORM=xcb "$gui" --screenshot "$2" --state "$3"
}
for state in "${states[@]}"; do
  if [ "$state" = laptop ]; then
    shot 1366x768 docs/img/gui_laptop.png messages
  else
    shot 1920x1080 "docs/img/gui_$state.png" "$state"
  fi
done
