#!/usr/bin/env bash
# Fuzzes every target (or those named) for SECONDS each (600 by default), one after the other,
# with libFuzzer and AddressSanitizer on nightly Rust; grows fuzz/corpus/TARGET, then minimizes
# it (cargo fuzz cmin) so that the committed corpus keeps the coverage in few files. Prints one
# Markdown row per target: executions, coverage (libFuzzer's cov and ft counters), corpus
# files, and crashes (saved in fuzz/artifacts/TARGET).
#
#     cargo install cargo-fuzz
#     fuzz/fuzz-all.sh 600                 # every target, 10 minutes each
#     fuzz/fuzz-all.sh 60 ply far_field    # two targets, a minute each
set -uo pipefail
cd "$(dirname "$0")"
seconds="${1:-600}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    mapfile -t targets < <(cargo +nightly fuzz list)
fi
echo "| target | seconds | executions | cov | ft | corpus files | crashes |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for t in "${targets[@]}"; do
    mkdir -p "corpus/$t" "artifacts/$t"
    log="$(mktemp)"
    cargo +nightly fuzz run -O "$t" "corpus/$t" -- \
        -max_total_time="$seconds" -print_final_stats=1 -rss_limit_mb=4096 \
        -timeout=20 >"$log" 2>&1
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
    last=$(grep -E '#[0-9]+.*cov:' "$log" | tail -1)
    cov=$(grep -o 'cov: [0-9]*' <<<"$last" | grep -o '[0-9]*')
    ft=$(grep -o 'ft: [0-9]*' <<<"$last" | grep -o '[0-9]*')
    crashes=$(find "artifacts/$t" -type f | wc -l)
    # Minimize what libFuzzer added (files named by their hash); the seeds and the inputs that
    # once crashed (named by hand) stay as they are.
    keep="$(mktemp -d)"
    find "corpus/$t" -type f ! -regex '.*/[0-9a-f]\{40\}$' -exec mv {} "$keep" \;
    cargo +nightly fuzz cmin -O "$t" "corpus/$t" >/dev/null 2>&1
    mv "$keep"/* "corpus/$t/" 2>/dev/null
    rmdir "$keep"
    files=$(find "corpus/$t" -type f | wc -l)
    echo "| $t | $seconds | ${execs:-?} | ${cov:-?} | ${ft:-?} | $files | $crashes |"
    rm -f "$log"
done
