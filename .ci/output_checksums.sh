#!/usr/bin/env bash
# Runs every shipped job (configs/*.yaml) with one windplan binary into a scratch folder and
# prints the SHA-256 of every output file, one "hash  job/file" line each, sorted. Two binaries
# (say, before and after a refactoring) give the same list exactly when every output file of
# every shipped job is byte-identical:
#   .ci/output_checksums.sh OLD/build/windplan > old.txt
#   .ci/output_checksums.sh build/windplan > new.txt && diff old.txt new.txt
# Run both from the same checkout's root (jobs name their mandrel files relative to it, and
# manifest.json records the job file's absolute path).
set -euo pipefail
bin=$(realpath "$1")
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
for job in configs/*.yaml; do
  name=$(basename "$job" .yaml)
  if ! "$bin" run "$job" --out "$scratch/$name" --threads 2 >"$scratch/$name.log" 2>&1; then
    echo "FAILED  $name" ; sed 's/^/  /' "$scratch/$name.log" >&2
    continue
  fi
  (cd "$scratch" && find "$name" -type f -print0 | xargs -0 sha256sum)
done | sort -k2
