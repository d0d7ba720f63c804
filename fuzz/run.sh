#!/usr/bin/env bash
# Run gonio's reader fuzz targets, each seeded with the test fixtures of its format.
#   fuzz/run.sh [SECONDS_PER_TARGET] [TARGET...]     (default 600 s, every target)
# Needs cargo-fuzz (`cargo install cargo-fuzz`); on a stable toolchain RUSTC_BOOTSTRAP=1 lets it
# pass the sanitizer flags. Crashes land in fuzz/artifacts/TARGET/; each one found becomes a
# regression test beside the reader's other tests.
set -euo pipefail
cd "$(dirname "$0")"
seconds=${1:-600}
shift || true
data=../crates/surface/tests/data
declare -A seeds=(
  [x3p]="*.x3p" [sdf]="*.sdf" [gsf]="*.gsf" [gwyddion_ascii]="gwyddion-export-english.txt matrix-3.txt"
  [zygo]="*.dat" [wyko]="*.opd" [plu]="*.plu" [sur]="*.sur" [al3d]="*.al3d" [frt]="*.frt"
  [mnt]="*.mnt" [nms]="*.nms" [tmd]="*.tmd" [header_matrix]="matrix-4.txt" [xyz]="xyz-1.txt"
  [nanoscope]="*.di" [nid]="*.nid" [picoview]="*.mi" [wsxm]="*.top *.stp" [ibw]="*.ibw"
  [opdx]="*.opdx" [detect]="*"
)
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=("${!seeds[@]}")
# Build every target once (address sanitizer, coverage), then run the binaries directly.
RUSTC_BOOTSTRAP=1 cargo fuzz build -O
bin=target/x86_64-unknown-linux-gnu/release
for t in "${targets[@]}"; do
  mkdir -p "corpus/$t"
  set -f
  patterns=(${seeds[$t]})
  set +f
  for pattern in "${patterns[@]}"; do
    for f in $data/$pattern; do
      case "$f" in *.md) ;; *) cp -n "$f" "corpus/$t/" ;; esac
    done
  done
  largest=$(find "corpus/$t" -type f -printf '%s\n' | sort -n | tail -1)
  # Inputs up to the largest seed and a little more; allocations beyond 512 MiB are bugs here
  # (no fixture needs more than 40 MiB, and a reader checks every size against the input first).
  mkdir -p "artifacts/$t"
  "$bin/$t" "corpus/$t" -artifact_prefix="artifacts/$t/" \
    -max_total_time="$seconds" -max_len=$((largest + largest / 10 + 1024)) \
    -malloc_limit_mb=512 -rss_limit_mb=2048 -timeout=20 -print_final_stats=1
done
