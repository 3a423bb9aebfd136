#!/usr/bin/env bash
# Runs clang-tidy (Debian 12's, 14) with the checks of .clang-tidy on the C++ sources changed
# since a base revision, and fails, with file:line messages, on any finding.
# Usage: scripts/check-tidy.sh [--all | BASE] [-p BUILD_DIR] [-j JOBS]
#   BASE       a git revision (default: $CLOUDGRAPH_TIDY_BASE, else HEAD~1; where HEAD has no
#              parent every file is new and every file is checked). The changes are those of
#              the working tree against BASE, untracked files included.
#   --all      every *.cc under algo core nodes cli formats util python
#   -p DIR     the build directory whose compile_commands.json to use (default: build)
#   -j JOBS    clang-tidy processes at once (default: $CLOUDGRAPH_TIDY_JOBS, else nproc)
# A changed header is checked through a .cc that includes it (its own .cc where it has one).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"

all=0
base=${CLOUDGRAPH_TIDY_BASE:-}
build="$root/build"
jobs=${CLOUDGRAPH_TIDY_JOBS:-$(nproc)}
while [ $# -gt 0 ]; do
    case "$1" in
        --all) all=1 ;;
        -p) build=$2; shift ;;
        -j) jobs=$2; shift ;;
        -h | --help) sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        -*) echo "check-tidy: unknown option '$1' (--help)" >&2; exit 2 ;;
        *) base=$1 ;;
    esac
    shift
done
build=$(cd "$build" 2>/dev/null && pwd) ||
    { echo "check-tidy: no build directory (configure one: scripts/build.sh)" >&2; exit 2; }
db="$build/compile_commands.json"
[ -f "$db" ] || { echo "check-tidy: $db is missing (CMAKE_EXPORT_COMPILE_COMMANDS)" >&2; exit 2; }
command -v clang-tidy >/dev/null ||
    { echo "check-tidy: clang-tidy is missing (apt-get install clang-tidy, or scripts/install-deps.sh --tests)" >&2; exit 1; }

folders=(algo core nodes cli formats util python)
# The sources the build compiles (python/ only where the module is built).
in_db() { grep -qF "\"file\": \"$root/$1\"" "$db"; }

if [ "$all" = 1 ]; then
    mapfile -t changed < <(find "${folders[@]}" -name '*.cc' | sort)
    what="every source"
else
    if ! git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
        echo "check-tidy: not a git checkout: nothing to compare (--all checks every file)"
        exit 77  # ctest: skipped
    fi
    if [ -z "$base" ]; then
        if git rev-parse -q --verify HEAD~1 >/dev/null; then base=HEAD~1; else all=1; fi
    fi
    if [ "$all" = 1 ]; then
        mapfile -t changed < <(find "${folders[@]}" -name '*.cc' | sort)
        what="every source (HEAD has no parent)"
    else
        git rev-parse -q --verify "$base^{commit}" >/dev/null ||
            { echo "check-tidy: '$base' is not a revision" >&2; exit 2; }
        mapfile -t changed < <({
            git diff --name-only --diff-filter=d "$base" -- "${folders[@]}"
            git ls-files --others --exclude-standard -- "${folders[@]}"
        } | grep -E '\.(cc|h)$' | sort -u)
        what="the sources changed since $base ($(git rev-parse --short "$base"))"
    fi
fi

# A changed header stands for one translation unit that includes it: its own .cc, else a .cc
# that includes it, else one that includes a header that includes it (three levels deep).
unit_of() {
    local h=$1 depth=$2 g
    [ -f "${h%.h}.cc" ] && in_db "${h%.h}.cc" && { echo "${h%.h}.cc"; return; }
    while read -r g; do
        if [[ "$g" == *.cc ]]; then
            in_db "$g" && { echo "$g"; return; }
        elif [ "$depth" -lt 3 ] && g=$(unit_of "$g" $((depth + 1))) && [ -n "$g" ]; then
            echo "$g"
            return
        fi
    done < <(grep -rlF --include='*.cc' --include='*.h' "#include \"$h\"" "${folders[@]}" |
        sort -t. -k2,2 | grep -vxF "$h")
    return 0
}
files=()
skipped=0
for f in "${changed[@]}"; do
    [ -f "$f" ] || continue
    if [[ "$f" == *.h ]]; then
        cc=$(unit_of "$f" 1) || true
        [ -n "$cc" ] || { skipped=$((skipped + 1)); continue; }
        f=$cc
    elif ! in_db "$f"; then
        skipped=$((skipped + 1))
        continue
    fi
    files+=("$f")
done
if [ ${#files[@]} -gt 0 ]; then mapfile -t files < <(printf '%s\n' "${files[@]}" | sort -u); fi
note=""
[ "$skipped" -eq 0 ] || note=" ($skipped skipped: no translation unit in $build)"
if [ ${#files[@]} -eq 0 ]; then
    echo "check-tidy: 0 files checked: no C++ source among $what$note"
    exit 0
fi

# Findings in our headers, not in OpenVDB's, TBB's or the standard library's. Headers are
# reached through build/include/<folder>/<folder> (cmake/Layering.cmake): messages name them
# by their path in the checkout.
re() { printf '%s' "$1" | sed 's/[.[\*^$()+?{|]/\\&/g'; }
filter="^($(re "$root")|$(re "$build")/include/[a-z]+)/($(IFS='|'; echo "${folders[*]}"))/"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "check-tidy: checking ${#files[@]} file(s), $what, $jobs at a time$note"
start=$SECONDS
export build out filter
printf '%s\n' "${files[@]}" | xargs -P "$jobs" -I{} sh -c '
    log="$out/$(echo "$1" | tr / _).log"
    if clang-tidy -p "$build" --quiet --header-filter="$filter" "$1" >"$log" 2>&1; then
        rm -f "$log"
    fi' sh {} || true

shopt -s nullglob
logs=("$out"/*.log)
failed=${#logs[@]}
# A finding in a header shows once, however many of the files checked include it.
if [ "$failed" -gt 0 ]; then
    grep -hvE '^[0-9]+ (warnings?|errors?)( and [0-9]+ errors?)? generated\.$|^Suppressed [0-9]+ warnings|^Use -header-filter|treated as errors?$' "${logs[@]}" |
        sed -e "s#^$build/include/[a-z]*/##" -e "s#^$root/##" |
        awk 'BEGIN { show = 1 } /^[^ ]+:[0-9]+:[0-9]+: (warning|error|fatal error): / { show = !seen[$0]++ } show' || true
fi
if [ "$failed" -gt 0 ]; then
    echo "check-tidy: findings in $failed of ${#files[@]} file(s) checked (.clang-tidy says which checks; fix them, or NOLINT(check) with a reason)" >&2
    exit 1
fi
echo "check-tidy: ${#files[@]} file(s) checked, no findings ($((SECONDS - start)) s)"
