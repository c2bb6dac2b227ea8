#!/usr/bin/env bash
# Runs every recipe of README.md (or of another page, DOC) as a newcomer would paste it: each
# ```sh block of the "## Recipes" section, in a fresh empty folder that has the repository's
# samples/ beside it, with the built demlight first on PATH. Fails when a recipe fails, when a
# file it names with -o is not there afterwards, or when the section has fewer than MIN recipes
# (default 5).
# Usage: tests/readme_recipes.sh BIN_DIR [REPO_DIR [DOC [MIN]]]
# (ctest runs it as ReadmeRecipes, and on docs/solar.md as SolarRecipes)
set -euo pipefail
bin_dir=$(cd "$1" && pwd)
repo=$(cd "${2:-$(dirname "$0")/..}" && pwd)
readme="$repo/${3:-README.md}"
least=${4:-5}

work=$(mktemp -d "${TMPDIR:-/tmp}/demlight_recipes.XXXXXX")
trap 'rm -rf "$work"' EXIT

# One file per code block of the section, in order.
awk -v dir="$work" '
  /^## / { inside = ($0 == "## Recipes"); if (file != "") { close(file); file = "" } }
  inside && /^```sh$/ { n++; file = sprintf("%s/recipe_%d.sh", dir, n); next }
  inside && /^```$/ && file != "" { close(file); file = ""; next }
  file != "" { print > file }
' "$readme"

recipes=("$work"/recipe_*.sh)
[ -e "${recipes[0]}" ] || { echo "$readme: no \`\`\`sh block under '## Recipes'" >&2; exit 1; }
if [ ${#recipes[@]} -lt "$least" ]; then
  echo "$readme: ${#recipes[@]} recipes under '## Recipes', expected at least $least" >&2
  exit 1
fi

export PATH="$bin_dir:$PATH"
failed=0
for recipe in "${recipes[@]}"; do
  name=$(basename "$recipe" .sh)
  here="$work/$name.run"
  mkdir "$here"
  ln -s "$repo/samples" "$here/samples"
  start=$SECONDS
  if ! (cd "$here" && bash -euo pipefail "$recipe" >"$here.log" 2>&1); then
    echo "FAILED $name:"; cat "$recipe"; echo "--- output:"; cat "$here.log"
    failed=1
    continue
  fi
  # Every output the recipe names (-o PATH) must exist.
  for out in $(grep -oE '(^|[[:space:]])-o[[:space:]]+[^[:space:]]+' "$recipe" | awk '{print $2}'); do
    if [ ! -e "$here/$out" ]; then
      echo "FAILED $name: no $out after the run"; cat "$recipe"
      failed=1
    fi
  done
  echo "ok $name ($((SECONDS - start)) s): $(head -1 "$recipe")"
done
exit $failed
