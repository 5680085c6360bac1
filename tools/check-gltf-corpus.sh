#!/usr/bin/env bash
# Runs obscura-render on every glTF file of Debian's assimp-testmodels and prints one Markdown table row per file:
# exit status and the first line of the message (docs/robustness.md holds the output).
set -uo pipefail
cd "$(dirname "$0")/.."
root=/usr/share/assimp/models/glTF2
echo "| file | status | message |"
echo "|---|---|---|"
find "$root" -type f \( -name '*.gltf' -o -name '*.glb' \) | sort | while read -r file; do
  # A radius given, so that stderr holds only what the loader says (without one, a note names the default radius).
  message=$(build/obscura-render --scene "$file" --size 64x48 --ao.radius 1 --out /tmp/obscura-corpus.png \
            2>&1 >/dev/null)
  status=$?
  message=${message%%$'\n'*}
  message=${message//$root\//}
  message=${message//|/\\|}
  echo "| ${file#$root/} | $status | ${message:-loaded} |"
done
