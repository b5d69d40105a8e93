#!/usr/bin/env bash
# Makefile.cases reruns only what is out of date: a second make does nothing; touching the scene
# reruns the whole chain. Runs on a copy of the workflow files with the small test scene.
set -eu
root=$1 build=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cp -r "$root/Makefile.cases" "$root/workflows" "$root/scripts" "$tmp/"
mkdir -p "$tmp/tests/data" && cp "$root/tests/data/small.toml" "$tmp/tests/data/"
cd "$tmp"
mk() { make -f Makefile.cases BUILD="$build" OUT=out QUICK_SCENE=tests/data/small.toml quickstart-outputs "$@"; }
mk > log1 2>&1 || { cat log1; exit 1; }
for f in settled.h5 shaken.h5 displacement.vtu profile.csv profile.png stress.vtu chains.vtp fields.vti stress.csv stress.png; do [ -s out/quickstart/$f ] || { echo "missing $f"; exit 1; }; done
stamp() { stat -c %Y.%y out/quickstart/settled.h5 out/quickstart/shaken.h5 out/quickstart/profile.csv out/quickstart/profile.png out/quickstart/stress.csv out/quickstart/stress.png; }
before=$(stamp)
mk > log2 2>&1
if grep -q -E "gen-primary|run-stage|post-macro|plot_profile|plot_stress" log2; then echo "second make reran something:"; cat log2; exit 1; fi
[ "$before" = "$(stamp)" ] || { echo "outputs changed on a second make"; exit 1; }
sleep 1.1
touch tests/data/small.toml
mk > log3 2>&1
for t in gen-primary run-stage post-macro plot_profile plot_stress; do grep -q "$t" log3 || { echo "touching the scene did not rerun $t"; cat log3; exit 1; }; done
echo "make incremental ok"
