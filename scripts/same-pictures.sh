#!/usr/bin/env bash
# Same pictures: renders the paper's scenes (scenes/*.json of OLD_COMMIT) with OLD_COMMIT's build and with the
# working tree's, and compares every output file byte for byte (render.json without the fields that record the
# run: times, rates, date, command line, output folder, threads). New renders are made with 1 and with 2 threads.
# Prints one line per scene and exits 1 when any file differs. The check for a refactoring or a speed-up that must
# not change any picture.
#
#   usage: scripts/same-pictures.sh OLD_COMMIT [render options, e.g. --width 320 --height 240 --formats all]
#
# Meshes come from $SPECTRAL_MODELS (default ../shared/models beside the checkout). OLD_COMMIT is built in
# /tmp/bench-compare-SHA (shared with scripts/bench-compare.sh); SAME_PICTURES_OLD_DLL=PATH/spectral.dll uses a build
# made before instead.
set -euo pipefail
old=${1:?usage: scripts/same-pictures.sh OLD_COMMIT [render options]}; shift
repo=$(git rev-parse --show-toplevel); cd "$repo"
oldsha=$(git rev-parse --verify "$old^{commit}")
export SPECTRAL_MODELS=${SPECTRAL_MODELS:-$(cd "$repo/.." && pwd)/shared/models}
oldtree=/tmp/bench-compare-${oldsha:0:12}
[[ -d $oldtree ]] || git worktree add --detach "$oldtree" "$oldsha" >/dev/null
if [[ -n ${SAME_PICTURES_OLD_DLL:-} ]]; then OLD=$SAME_PICTURES_OLD_DLL
else
    dotnet build -c Release -v q -nologo "$oldtree/src/SpectralRenderer.Cli" >/dev/null
    OLD=$oldtree/src/SpectralRenderer.Cli/bin/Release/net10.0/spectral.dll
fi
dotnet build -c Release -v q -nologo "$repo/src/SpectralRenderer.Cli" >/dev/null
NEW=$repo/src/SpectralRenderer.Cli/bin/Release/net10.0/spectral.dll
out=$(mktemp -d /tmp/same-pictures.XXXXXX); trap 'rm -rf "$out"' EXIT
# render.json fields that describe the run rather than the picture.
volatile='"(created_utc|render|mrays_per_s|command_line|load_s|build_s|build|write_s|total_s|output|elapsed_s|threads|light_transfer_s)":'
differ=0
for scene in "$oldtree"/scenes/*.json; do
    name=$(basename "$scene" .json)
    dotnet "$OLD" render "$scene" -o "$out/$name.old" --quiet --threads 2 "$@"
    for t in 1 2; do
        dotnet "$NEW" render "$scene" -o "$out/$name.new$t" --quiet --threads "$t" "$@"
        bad=()
        while IFS= read -r f; do
            rel=${f#"$out/$name.old/"}
            if [[ $rel == render.json ]]; then
                cmp -s <(grep -Ev "$volatile" "$f") <(grep -Ev "$volatile" "$out/$name.new$t/$rel") || bad+=("$rel")
            else
                cmp -s "$f" "$out/$name.new$t/$rel" || bad+=("$rel")
            fi
        done < <(find "$out/$name.old" -type f | sort)
        n_old=$(find "$out/$name.old" -type f | wc -l); n_new=$(find "$out/$name.new$t" -type f | wc -l)
        [[ $n_old == "$n_new" ]] || bad+=("file count $n_old vs $n_new")
        if ((${#bad[@]})); then differ=1; echo "$name threads=$t: DIFFERENT: ${bad[*]}"; else echo "$name threads=$t: identical ($n_old files)"; fi
    done
    rm -rf "$out/$name".*
done
exit $differ
