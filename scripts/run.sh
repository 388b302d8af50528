#!/usr/bin/env bash
# gbump's main job end to end on the built-in default scene (torus_caps, paper Fig. 4) and the
# configuration derived from it: render (golden, f64 references, heat map), generate RTL and
# ROM files, dump vectors, lint, regress on both simulators, and render the scene through the
# RTL, which must equal the golden image bit for bit. Output goes to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-tools.sh
cargo build --release --quiet
g=./target/release/gbump
s=torus_caps
$g render --scene $s --out out/render
$g rtl --scene $s --out out/rtl
$g rom --scene $s --out out/rom
$g vectors --source scene:$s --out out/vectors
$g vectors --source corners --scene $s --out out/vectors
$g lint --scene $s --work out/lint
$g regress --sim both --scene $s --work out/regress --junit out/regress/junit.xml
$g render --scene $s --rtl --out out/render
echo "done: images in out/render, RTL in out/rtl, ROMs in out/rom, vectors in out/vectors, JUnit in out/regress/junit.xml"
