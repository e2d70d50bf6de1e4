#!/usr/bin/env bash
# Byte-identical check of a restructure: renders the paper's scenes (scenes/*.json) with the build of
# a given commit and with the working tree, and compares the outputs byte for byte (cmp).
#
#   scripts/compare-scenes.sh COMMIT [--width W --height H] [--formats LIST] [--keep]
#
# Meshes come from $SPECTRAL_MODELS (e.g. SPECTRAL_MODELS=/work/shared/models). Compared: spectral.npy
# of every scene, and every other file both builds wrote except render.json (which records timings).
# COMPARE_BASE_BIN=DIR uses an existing build of COMMIT instead of building it.
# Exit 0 when every spectral.npy is identical, 1 otherwise.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
base=${1:?usage: scripts/compare-scenes.sh COMMIT [--width W --height H] [--formats LIST] [--keep]}
shift
width=""; height=""; formats="npy,png,aov"; keep=0
while [ $# -gt 0 ]; do
  case "$1" in
    --width) width=$2; shift 2 ;;
    --height) height=$2; shift 2 ;;
    --formats) formats=$2; shift 2 ;;
    --keep) keep=1; shift ;;
    *) echo "compare-scenes: unknown option '$1'" >&2; exit 2 ;;
  esac
done
: "${SPECTRAL_MODELS:?set SPECTRAL_MODELS to the folder holding the meshes (stanford-bunny.obj, igea.ply)}"
export SPECTRAL_MODELS
work=$(mktemp -d /tmp/compare-scenes.XXXXXX)
[ "$keep" = 1 ] || trap 'rm -rf "$work"' EXIT

if [ -n "${COMPARE_BASE_BIN:-}" ]; then   # a build of COMMIT made before (saves a rebuild)
  ln -s "$COMPARE_BASE_BIN" "$work/bin-base"
else
  echo "building $base ..."
  mkdir -p "$work/src-base"
  git -C "$repo" archive "$base" | tar -x -C "$work/src-base"
  dotnet build "$work/src-base/src/SpectralRenderer.Cli" -c Release -o "$work/bin-base" -v q -nologo >"$work/build-base.log" 2>&1 \
    || { cat "$work/build-base.log"; exit 1; }
fi
echo "building the working tree ..."
dotnet build "$repo/src/SpectralRenderer.Cli" -c Release -o "$work/bin-tree" -v q -nologo >"$work/build-tree.log" 2>&1 \
  || { cat "$work/build-tree.log"; exit 1; }

size=()
[ -n "$width" ] && size+=(--width "$width")
[ -n "$height" ] && size+=(--height "$height")
differ=0; scenes=0
for scene in "$repo"/scenes/*.json; do
  name=$(basename "$scene" .json)
  for which in base tree; do
    dotnet "$work/bin-$which/spectral.dll" render "$scene" -o "$work/out-$which/$name" --formats "$formats" "${size[@]}" --quiet
  done
  scenes=$((scenes + 1))
  if cmp -s "$work/out-base/$name/spectral.npy" "$work/out-tree/$name/spectral.npy"; then
    npy="identical"
  else
    npy="DIFFERENT"; differ=$((differ + 1))
  fi
  others=""
  while IFS= read -r f; do
    [ "$f" = spectral.npy ] || [ "$f" = render.json ] && continue
    if [ -f "$work/out-tree/$name/$f" ]; then
      cmp -s "$work/out-base/$name/$f" "$work/out-tree/$name/$f" || others+=" $f differs;"
    else
      others+=" $f only in $base;"
    fi
  done < <(cd "$work/out-base/$name" && find . -type f | sed 's|^\./||' | sort)
  echo "$name: spectral.npy $npy${others:+ (other files:$others)}"
done
echo "compare-scenes: $scenes scenes, $((scenes - differ)) spectral.npy identical, $differ different ($base vs working tree${width:+, ${width}x${height}})"
[ "$differ" = 0 ]
