#!/usr/bin/env bash
# fuzz_seeds_current: the seeds targets/make_seeds.c generates, written afresh
# into an empty copy of the corpus layout, must equal the committed ones byte
# for byte. A protocol change (a new settings key, a new FRAME attribute) that
# changes what an encoder writes leaves the committed seeds stale until they are
# regenerated (README.md, "The seed corpus": fuzz_make_seeds tests/fuzz/corpus).
# Usage: check_seeds.sh MAKE_SEEDS CORPUS_DIR WORK_DIR
set -euo pipefail
make_seeds=$1 corpus=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
for dir in "$corpus"/*/; do
  mkdir -p "$work/$(basename "$dir")"
done
"$make_seeds" "$work"
written=0 stale=0
while IFS= read -r -d '' file; do
  rel=${file#"$work"/}
  written=$((written + 1))
  if [ ! -f "$corpus/$rel" ]; then
    echo "missing seed: tests/fuzz/corpus/$rel (make_seeds.c writes it, the corpus lacks it)"
    stale=$((stale + 1))
  elif ! cmp -s "$file" "$corpus/$rel"; then
    echo "stale seed: tests/fuzz/corpus/$rel differs from what make_seeds.c writes now"
    stale=$((stale + 1))
  fi
done < <(find "$work" -type f -print0)
if [ "$written" -eq 0 ]; then
  echo "make_seeds wrote nothing"
  exit 1
fi
if [ "$stale" -ne 0 ]; then
  echo "$stale of $written generated seeds are stale: regenerate them (tests/fuzz/README.md, 'The seed corpus')"
  exit 1
fi
echo "all $written generated seeds are current"
