#!/usr/bin/env bash
# Same outputs beyond the render: for the paper's scenes (scenes/*.json of OLD_COMMIT), OLD_COMMIT's build and the
# working tree's each run the commands that read or assemble renders —
#   render --formats all,lights (all for a scene of another integrator than whitted: no per-light transfer);
#   relight (every light to CIE A, and --metrics);  render --shard 0/2, 1/2 + merge;
#   camera (nikon-d5100, wheel-6, noise on) and recover --method all on the §3.1 and §3.4 scenes —
# and every file they write is compared byte for byte (JSON files without the fields that record the run: times,
# rates, date, command line, folders, threads, build id). Prints one line per scene and step; exits 1 when any differs.
# The check, beside scripts/same-pictures.sh, for a refactoring that must not change any output.
#
#   usage: scripts/same-outputs.sh OLD_COMMIT [render options, e.g. --width 160 --height 120]
#
# Meshes from $SPECTRAL_MODELS (default ../shared/models beside the checkout). OLD_COMMIT is built in
# /tmp/bench-compare-SHA (shared with scripts/bench-compare.sh); SAME_PICTURES_OLD_DLL=PATH/spectral.dll uses a build
# made before instead.
set -euo pipefail
old=${1:?usage: scripts/same-outputs.sh OLD_COMMIT [render options]}; shift
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
out=$(mktemp -d /tmp/same-outputs.XXXXXX); trap 'rm -rf "$out"' EXIT
# JSON fields that describe the run rather than the result.
volatile='"(created_utc|render|mrays_per_s|command_line|load_s|build_s|build|write_s|total_s|output|elapsed_s|threads|light_transfer_s|compute_s|source|folder|path|camera_folder|render_folder|from|from_created_utc)":'

# run TAG DLL SCENE NAME: every command of the list for one scene into $out/NAME.TAG/.
run() {
    local tag=$1 dll=$2 scene=$3 name=$4 d="$out/$4.$1"
    local lights=() l formats=all,lights integrator
    # The per-light transfer (lights, relight) is the Whitted model's: another integrator's scene renders without it.
    integrator=$(python3 -c 'import re,sys; m=re.search(r"\"integrator\"\s*:\s*(?:\{[^}]*\"type\"\s*:\s*)?\"(\w+)\"", open(sys.argv[1]).read()); print(m.group(1) if m else "whitted")' "$scene")
    [[ $integrator == whitted ]] || formats=all
    dotnet "$dll" render "$scene" -o "$d/render" --quiet --threads 2 --formats "$formats" "${opts[@]}"
    [[ $formats == all ]] || mapfile -t lights < <(python3 -c 'import json,sys; [print(l["name"]) for l in json.load(open(sys.argv[1]))["lights"]]' "$d/render/render.json")
    if ((${#lights[@]})); then
        local relight=()
        for l in "${lights[@]}"; do relight+=(--light "$l=A"); done
        dotnet "$dll" relight "$d/render" "${relight[@]}" --metrics -o "$d/relit" --quiet >/dev/null
    fi
    # A shard cannot choose an automatic exposure from the whole image: it gets the one the whole render chose.
    local whole=$scene
    if grep -Eq '"exposure": *"auto"' "$scene"; then
        whole="$out/$name.exposure.json"   # one path for both builds (render.json names the scene file)
        sed -E "s/\"exposure\": *\"auto\"/\"exposure\": $(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["colour"]["exposure"])' "$d/render/render.json")/" "$scene" >"$whole"
    fi
    dotnet "$dll" render "$whole" -o "$d/shard1" --quiet --threads 2 --shard 0/2 "${opts[@]}"
    dotnet "$dll" render "$whole" -o "$d/shard2" --quiet --threads 2 --shard 1/2 "${opts[@]}"
    dotnet "$dll" merge "$d/shard2" "$d/shard1" -o "$d/merged" --quiet
    rm -rf "$d/shard1" "$d/shard2"
    case $name in paper-3.1-*|paper-3.4-*)
        for sensor in nikon-d5100 wheel-6; do
            dotnet "$dll" camera "$d/render" --sensor "$sensor" -o "$d/camera-$sensor" >/dev/null
            dotnet "$dll" recover "$d/camera-$sensor" --method all >/dev/null
        done;;
    esac
}

opts=("$@")
differ=0
for scene in "$oldtree"/scenes/*.json; do
    name=$(basename "$scene" .json)
    run old "$OLD" "$scene" "$name"
    run new "$NEW" "$scene" "$name"
    bad=()
    while IFS= read -r f; do
        rel=${f#"$out/$name.old/"}
        g="$out/$name.new/$rel"
        if [[ ! -f $g ]]; then bad+=("$rel (missing)")
        elif [[ $rel == *.json ]]; then
            cmp -s <(grep -Ev "$volatile" "$f") <(grep -Ev "$volatile" "$g") || bad+=("$rel")
        else
            cmp -s "$f" "$g" || bad+=("$rel")
        fi
    done < <(find "$out/$name.old" -type f | sort)
    n_old=$(find "$out/$name.old" -type f | wc -l); n_new=$(find "$out/$name.new" -type f | wc -l)
    [[ $n_old == "$n_new" ]] || bad+=("file count $n_old vs $n_new")
    steps=$(find "$out/$name.old" -mindepth 1 -maxdepth 1 -type d -printf '%f ' | xargs -n1 | sort | xargs)
    if ((${#bad[@]})); then differ=1; echo "$name: DIFFERENT: ${bad[*]}"; else echo "$name: identical ($n_old files: $steps)"; fi
    rm -rf "$out/$name".*
done
exit $differ
