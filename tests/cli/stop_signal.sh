#!/usr/bin/env bash
# SIGTERM (what batch schedulers, `timeout` and container stops send) keeps the finished wavelengths exactly as
# Ctrl-C does: the output is written, marked partial, and the exit code is 128 + 15.
set -u
program="$1"
out="$(mktemp -d)/stopped.json"
# Minutes of work at --stderr 0.00005 (16x the rays of 0.0002, which finished in ~3 s): the signal after 2 s finds it
# running on a much faster machine too.
"$program" spectrum --preset biospec-lightly --wavelengths 400:700:1 --stderr 0.00005 --output "$out" 2>/dev/null &
pid=$!
sleep 2
kill -TERM "$pid"
wait "$pid"
rc=$?
[ "$rc" -eq 143 ] || { echo "exit $rc, expected 143"; exit 1; }
[ -f "$out" ] || { echo "no output written"; exit 1; }
grep -q '"partial": true' "$out" || { echo "output not marked partial"; exit 1; }
echo "SIGTERM kept $(grep -c '^' "$out") lines, marked partial"
