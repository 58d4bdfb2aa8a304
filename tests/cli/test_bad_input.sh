#!/usr/bin/env bash
# The bad-input suite: every class of bad usage and bad input `sessile` can
# be given, one table line per case.  Each case runs in a fresh temporary
# folder as its working directory (XDG_CACHE_HOME elsewhere) and must
#   (a) exit with the expected code: 2 for bad usage or input, 1 for a
#       runtime failure (a stdout write error);
#   (b) print exactly ONE line on stderr, containing "error" and matching the
#       case's regular expression, and nothing on stdout;
#   (c) write nothing: the folder's listing (names, types, modes, sha256 of
#       every file, hidden ones included) is the same afterwards -- so an
#       --out DIR or --resume DIR inside it is not created, and a folder the
#       case prepared (a non-run folder, an earlier run) is unchanged.
# A case expecting exit 0 (configs merged in order) checks its regex against
# stdout instead, with stderr empty.  Every case runs under `timeout 20`: a
# FIFO or a device given as a config must not hang.  No grow case gets as far
# as a growth run: all fail before any work (a few create the Vulkan device
# first, e.g. to refuse a run directory).
#
# Table lines:  EXIT | REGEX | SETUP | ARGS
#   REGEX is an extended regex (grep -E), without " | " inside;
#   SETUP prepares the case folder: - (nothing), nonrun (other/ holding a
#   user's file), prevrun (prev/ holding a completed `sessile sphere` run),
#   emptydir (e/), file (a regular file 'file'), full (stdout is /dev/full),
#   cpudev (skipped unless the default device is a CPU one, e.g. lavapipe),
#   png (in.png and other.png, pictures, and link.png -> in.png), truncrun
#   (prev/ as prevrun with its final.ply cut to 300 bytes);
#   ARGS are shell words (quotes work; $F is the folder of fixture files).
# Usage: test_bad_input.sh path/to/sessile
set -u
S="$1"
. "$(dirname "$0")/../common/harness.sh"
S="$(cd "$(dirname "$S")" && pwd)/$(basename "$S")"
export XDG_CACHE_HOME="${XDG_CACHE_HOME:-$T/cache}"
mkdir -p "$XDG_CACHE_HOME"

# --- fixtures (outside every case folder) -------------------------------------
F="$T/fix"
mkdir -p "$F/dir"
echo '{}' >"$F/ok.json"
echo '{"t_give": 0.1, "l_max": 3}' >"$F/a.json"
echo '{"t_give": 0.3}' >"$F/b.json"
echo '{"noise": 0.1, "level": 2}' >"$F/sa.json"
echo '{"noise": 0.3}' >"$F/sb.json"
echo '{"nutrient_ksp_rtol": 1e-6, "linear_rtol": 1e-7}' >"$F/linear_both.json"
mkfifo "$F/fifo" "$F/fifo.png" "$F/fifo.exr" "$F/fifo.ply"
# L-system grammars whose numbers come out NaN at derivation (line 4 each)
printf 'iterations: 2\nangle: 20\naxiom: F(1)\nF(x) -> F(x) [ +(20) F(sqrt(-x)) ]\n' >"$F/nan_param.lsys"
printf 'iterations: 2\nangle: 20\naxiom: F(1)\nF(x) : sqrt(-x) -> F(x) [ +(20) F(1) ]\n' >"$F/nan_cond.lsys"
printf 'iterations: 2\nangle: 20\naxiom: F(1)\nF(x) -(sqrt(-x))-> F(x) F(1)\nF(x) -(1)-> F(x)\n' >"$F/nan_weight.lsys"
printf 'iterations: 2\nangle: 20\n\naxiom: F(1e308 * 10)\n' >"$F/inf_axiom.lsys"
long=$(printf 'n%.0s' $(seq 5000)) # a 5000-character file name
echo 'not an EXR' >"$F/garbage.exr"
: >"$F/empty.json"
echo '   ' >"$F/blank.json"
echo '[1, 2]' >"$F/array.json"
echo '3' >"$F/number.json"
echo '"t_give"' >"$F/string.json"
echo '{"t_give": 0.1, "t_give": 0.2}' >"$F/dup.json"
echo '{} x' >"$F/trailing.json"
echo '{}{}' >"$F/two.json"
printf '{"t_give": 0.1}\0\n' >"$F/nul_after.json"
printf '{"t_\0give": 0.1}\n' >"$F/nul_inside.json"
echo '{"nope": 1}' >"$F/unknown.json"
echo '{"diffusion_limited": 1}' >"$F/bool_as_1.json"
echo '{"skeletal_growth": 1}' >"$F/enum_as_number.json"
echo '{"t_give": "0.1"}' >"$F/number_as_string.json"
echo '{"t_give": null}' >"$F/null.json"
echo '{"t_give": {"value": 0.1}}' >"$F/object_value.json"
echo '{"box_resolution": 2.5}' >"$F/nonintegral.json"
echo '{"box_resolution": 1e300}' >"$F/int_huge.json"
echo '{"t_give": 2}' >"$F/range.json"
echo '{"l_max": 1e999}' >"$F/overflow.json"
echo '{"t_give": NaN}' >"$F/nan.json"
echo '{"t_give": 0x1p-3}' >"$F/hexfloat.json"
echo '{"t_give": 0.1,}' >"$F/comma.json"
echo "{'t_give': 0.1}" >"$F/single_quotes.json"
echo '{"skeletal_growth": "axinellid"}' >"$F/enum_unknown.json"
echo '{"kinetic_order": 0}' >"$F/open_bound.json"
python3 -c 'print("{\"t_give\": " + "[" * 20000 + "]" * 20000 + "}")' >"$F/deep.json"
python3 -c 'print("{\"t_give\": 0.1" + " " * (1 << 20) + "}")' >"$F/large.json"
echo '{"level": "3"}' >"$F/sphere_level_string.json"
echo '{"radius": 1e7}' >"$F/sphere_radius_range.json"
echo '{"level": 3, "wat": 1}' >"$F/sphere_unknown.json"
# a completed sphere run to copy into a case folder
"$S" sphere --out "$F/prevrun" --iterations 1 --every 0 --quiet >/dev/null 2>"$T/prevrun.err" ||
  { echo "FAIL setup: 'sessile sphere' cannot write a run to test against: $(cat "$T/prevrun.err")"; fails=$((fails + 1)); }
# the default device is a CPU one (lavapipe): its small heap is refused late
cpudev=0
"$S" devices 2>/dev/null | grep -A1 '^\* ' | grep -q 'type: cpu' && cpudev=1

# --- the cases ----------------------------------------------------------------
cases=$(cat <<'CASES'
# unknown commands and options
2 | unknown command 'frobnicate' | - | frobnicate
2 | unknown command '' | - | ''
2 | no command given | - |
2 | unknown option '--bogus' | - | --bogus grow
2 | grow: error: unknown option '--bogus' | - | grow --bogus
2 | unknown option 'extra' | - | grow extra
2 | unknown option '-x' | - | grow -x
2 | grow: error: --print-config takes no value \('--print-config=1'\) | - | grow --print-config=1
2 | unknown option '--' | - | grow -- --print-config
2 | sphere: error: unknown option '--bogus' | - | sphere --bogus
2 | sphere: error: unknown option '--preset' | - | sphere --preset radiate --print-config
2 | sphere: error: unknown option '--slices' | - | sphere --slices x --print-config
2 | version: error: takes no arguments | - | version extra
2 | unknown preset 'coral' | - | grow --preset coral --print-config
# options missing their values
2 | --out needs a value | - | grow --out
2 | --set needs a value | - | grow --set
2 | --config needs a value | - | grow --config
2 | --seed needs a value | - | grow --seed
2 | --iterations needs a value | - | grow --iterations
2 | --every needs a value | - | grow --every
2 | --resume needs a value | - | grow --resume
2 | --preset needs a value | - | grow --preset
2 | --slices needs a value | - | grow --slices
2 | --device needs a value | - | grow --device
2 | --precision needs a value | - | --precision
2 | sphere: error: --out needs a value | - | sphere --out
2 | sphere: error: --iterations needs a value | - | sphere --iterations
# option values starting with "--" are options, not values
2 | --out needs a value | - | grow --out --print-config
2 | --out needs a value | - | grow --print-config --out --force
2 | --config needs a value | - | grow --config --print-config
2 | --set needs a value | - | grow --set --quiet --print-config
2 | --seed needs a value | - | grow --seed --print-config
2 | --resume needs a value | - | grow --resume --force
2 | --slices needs a value | - | grow --slices --print-config
2 | --device needs a value | - | grow --device --print-config
2 | sphere: error: --out needs a value | - | sphere --out --print-config
2 | sphere: error: --resume needs a value | - | sphere --resume --iterations 3
# --seed: 0..2^64-1, decimal digits only
2 | --seed: '-1' is not an integer in 0\.\.18446744073709551615 | - | grow --seed -1 --print-config
2 | --seed: 'abc' is not an integer | - | grow --seed abc --print-config
2 | --seed: '18446744073709551616' is not an integer | - | grow --seed 18446744073709551616 --print-config
2 | --seed: '99999999999999999999999' is not an integer | - | grow --seed 99999999999999999999999 --print-config
2 | --seed: '\+1' is not an integer | - | grow --seed +1 --print-config
2 | --seed: ' 1' is not an integer | - | grow --seed ' 1' --print-config
2 | --seed: '1 ' is not an integer | - | grow --seed '1 ' --print-config
2 | --seed: '' is not an integer | - | grow --seed '' --print-config
2 | --seed: '1\.0' is not an integer | - | grow --seed 1.0 --print-config
2 | --seed: '0x10' is not an integer | - | grow --seed 0x10 --print-config
2 | --seed: '1e3' is not an integer | - | sphere --seed 1e3 --print-config
# --iterations / --every: 0..10000000
2 | --iterations: '-1' is not an integer in 0\.\.10000000 | - | grow --iterations -1
2 | --iterations: '1\.5' is not an integer | - | grow --iterations 1.5
2 | --iterations: '10000001' is not an integer | - | grow --iterations 10000001
2 | --iterations: '99999999999999999999' is not an integer | - | grow --iterations 99999999999999999999
2 | --iterations: '0x10' is not an integer | - | grow --iterations 0x10
2 | --iterations: ' 5' is not an integer | - | grow --iterations ' 5'
2 | --iterations: '1e3' is not an integer | - | grow --iterations 1e3
2 | --every: '-2' is not an integer | - | grow --every -2
2 | --every: 'abc' is not an integer | - | grow --every abc
2 | --every needs a value | - | grow --every ''
2 | --every: '\+3' is not an integer | - | grow --every +3
2 | sphere: error: --iterations: '-3' is not an integer | - | sphere --iterations -3
2 | sphere: error: --every: '2\.5' is not an integer | - | sphere --every 2.5
# --set KEY=VALUE: the key known, the value of the parameter's type, in range
2 | --set 't_give' must be KEY=VALUE | - | grow --out run --set t_give
2 | --set '=1' must be KEY=VALUE | - | grow --out run --set =1
2 | unknown parameter 'wat' | - | grow --out run --set wat=1
2 | unknown parameter 'T_GIVE' | - | grow --out run --set T_GIVE=0.1
2 | parameter t_give needs a value | - | grow --out run --set t_give=
2 | parameter box_resolution: '2\.5' is not an integer in \[1, 6\] | - | grow --out run --set box_resolution=2.5
2 | parameter probe_samples: '8e0' is not an integer | - | grow --out run --set probe_samples=8e0
2 | parameter box_cells_x: '99999999999999999999' is not an integer | - | grow --out run --set box_cells_x=99999999999999999999
2 | parameter diffusion_limited: 'maybe' is not true or false | - | grow --out run --set diffusion_limited=maybe
2 | parameter diffusion_limited: '2' is not true or false | - | grow --out run --set diffusion_limited=2
2 | parameter skeletal_growth: 'axinellid' is not one of radiate, halichondrid | - | grow --out run --set skeletal_growth=axinellid
2 | parameter domain: '1' is not one of immersed, conforming | - | grow --out run --set domain=1
2 | parameter probe: 'foo' is not one of flux, paper | - | grow --out run --set probe=foo
2 | parameter far_field: 'top' is not one of height, walls | - | grow --out run --set far_field=top
2 | parameter nutrient_pc_type: 'cg' is not one of mg, jacobi | - | grow --out run --set nutrient_pc_type=cg
2 | parameter nutrient_pc_type: 'cg' is not one of mg, jacobi | - | grow --out run --set nutrient_solver=cg
2 | parameter 'nutrient_ksp_rtol' is given twice .also as 'linear_rtol'. | - | grow --out run --config $F/linear_both.json
2 | parameter fluid_ksp_type: 'cg' is not one of gmres, bicgstab | - | grow --out run --set fluid_ksp_type=cg
2 | parameter fluid_pc_type: 'amg' is not one of none, jacobi, ilu0, block_jacobi, mg | - | grow --out run --set fluid_pc_type=amg
2 | parameter fluid_pc_type: 'ilu1' is not one of | - | grow --out run --set fluid_pc_type=ilu1
2 | parameter fluid_ksp_restart: '65' is not an integer in \[1, 64\] | - | grow --out run --set fluid_ksp_restart=65
2 | parameter fluid_ksp_max_it: '0' is not an integer in \[1, | - | grow --out run --set fluid_ksp_max_it=0
2 | parameter fluid_ksp_rtol: '1' is not a number in | - | grow --out run --set fluid_ksp_rtol=1
2 | parameter probe_distance: '0' is not a number in \(0, 100\] cm | - | grow --out run --set probe_distance=0
2 | far_field_height must be positive, or -1 for 4.8 sponge radii \(got 0\) | - | grow --out run --set far_field_height=0
2 | far_field_height \(1000 cm\) must not exceed the box top | - | grow --out run --set far_field_height=1000
2 | the sponge \(top at 6 cm\) plus one node spacing \(0\.6 cm\) must stay below far_field_height \(6\.3 cm\) | - | grow --out run --set far_field_height=6.3
2 | parameter kinetic_order: '0' is not a number in \(0, 100\] | - | grow --out run --set kinetic_order=0
2 | parameter growth_constant: '0' is not a number in \(0, | - | grow --out run --set growth_constant=0
2 | parameter fluid_max_seconds: '0' is not a number in \(0, | - | grow --out run --set fluid_max_seconds=0
2 | parameter box_resolution: '0' is not an integer in \[1, 6\] | - | grow --out run --set box_resolution=0
2 | parameter box_resolution: '7' is not an integer in \[1, 6\] | - | grow --out run --set box_resolution=7
2 | parameter t_give: '-1' is not a number in \[0, 1\] | - | grow --out run --set t_give=-1
2 | parameter fluid_viscosity: '0' is not a number | - | grow --out run --set fluid_viscosity=0
2 | parameter l_max: 'nan' is not a number | - | grow --out run --set l_max=nan
2 | parameter l_max: 'NaN' is not a number | - | grow --out run --set l_max=NaN
2 | parameter l_max: 'inf' is not a number | - | grow --out run --set l_max=inf
2 | parameter l_max: '-inf' is not a number | - | grow --out run --set l_max=-inf
2 | parameter l_max: 'Infinity' is not a number | - | grow --out run --set l_max=Infinity
2 | parameter growth_rate: '0x1p3' is not a number | - | grow --out run --set growth_rate=0x1p3
2 | parameter growth_rate: '0x10' is not a number | - | grow --out run --set growth_rate=0x10
2 | parameter growth_rate: '1e999' is not a number | - | grow --out run --set growth_rate=1e999
2 | parameter t_give: ' 0\.1' is not a number | - | grow --out run --set 't_give= 0.1'
2 | parameter t_give: '0\.1 ' is not a number | - | grow --out run --set 't_give=0.1 '
2 | parameter t_give: '1\.2\.3' is not a number | - | grow --out run --set t_give=1.2.3
2 | parameter t_give: '0,5' is not a number | - | grow --out run --set t_give=0,5
2 | parameter t_give: '1e' is not a number | - | grow --out run --set t_give=1e
2 | parameter t_give: '--1' is not a number | - | grow --out run --set t_give=--1
2 | parameter level: '0' is not an integer in \[1, 7\] | - | sphere --out run --set level=0
2 | parameter level: '8' is not an integer in \[1, 7\] | - | sphere --out run --set level=8
2 | parameter level: '2\.5' is not an integer | - | sphere --out run --set level=2.5
2 | parameter radius: '0' is not a number in \(0, 1e\+06\] cm | - | sphere --out run --set radius=0
2 | parameter radius: '-1' is not a number | - | sphere --out run --set radius=-1
2 | parameter radius: 'nan' is not a number | - | sphere --out run --set radius=nan
2 | parameter noise: '0\.6' is not a number in \[0, 0\.5\] | - | sphere --out run --set noise=0.6
2 | parameter noise: 'inf' is not a number | - | sphere --out run --set noise=inf
2 | unknown parameter 't_give' \('sessile sphere --print-config' | - | sphere --out run --set t_give=0.1
2 | --set 'level' must be KEY=VALUE | - | sphere --out run --set level
# --config FILE: a regular file holding one JSON object of known keys
2 | --config needs a file name | - | grow --out run --config ''
2 | cannot read config file '.*/missing\.json': No such file | - | grow --out run --config $F/ok.json --config $F/missing.json
2 | cannot read config file '.*/missing\.json' | - | grow --out run --config $F/missing.json --config $F/ok.json
2 | config file '.*/dir' is not a regular file | - | grow --out run --config $F/dir
2 | config file '.*/fifo' is not a regular file | - | grow --out run --config $F/fifo
2 | config file '/dev/zero' is not a regular file | - | grow --out run --config /dev/zero
2 | config file '/dev/null' is not a regular file | - | grow --out run --config /dev/null
2 | config file '/dev/stdin' is not a regular file | - | grow --out run --config /dev/stdin
2 | empty\.json':1:1: not valid JSON | - | grow --out run --config $F/empty.json
2 | blank\.json'.*not valid JSON | - | grow --out run --config $F/blank.json
2 | array\.json': must hold one JSON object | - | grow --out run --config $F/array.json
2 | number\.json': must hold one JSON object | - | grow --out run --config $F/number.json
2 | string\.json': must hold one JSON object | - | grow --out run --config $F/string.json
2 | dup\.json': parameter 't_give' is given twice | - | grow --out run --config $F/dup.json
2 | trailing\.json':1:4: not valid JSON | - | grow --out run --config $F/trailing.json
2 | two\.json':1:3: not valid JSON | - | grow --out run --config $F/two.json
2 | nul_after\.json': holds a NUL byte at offset 15 | - | grow --out run --config $F/nul_after.json
2 | nul_inside\.json': holds a NUL byte at offset 4 | - | grow --out run --config $F/nul_inside.json
2 | unknown\.json': unknown parameter 'nope' | - | grow --out run --config $F/unknown.json
2 | bool_as_1\.json': diffusion_limited must be true or false | - | grow --out run --config $F/bool_as_1.json
2 | enum_as_number\.json': skeletal_growth must be a string | - | grow --out run --config $F/enum_as_number.json
2 | number_as_string\.json': t_give must be a number | - | grow --out run --config $F/number_as_string.json
2 | null\.json': t_give must be a number | - | grow --out run --config $F/null.json
2 | object_value\.json': t_give must be a number | - | grow --out run --config $F/object_value.json
2 | nonintegral\.json': parameter box_resolution: '2\.5' is not an integer | - | grow --out run --config $F/nonintegral.json
2 | int_huge\.json': parameter box_resolution: .* is not an integer | - | grow --out run --config $F/int_huge.json
2 | range\.json': parameter t_give: '2' is not a number in \[0, 1\] | - | grow --out run --config $F/range.json
2 | overflow\.json': parameter l_max: .* is not a number | - | grow --out run --config $F/overflow.json
2 | nan\.json':1:[0-9]+: not valid JSON | - | grow --out run --config $F/nan.json
2 | hexfloat\.json':1:[0-9]+: not valid JSON | - | grow --out run --config $F/hexfloat.json
2 | comma\.json':1:[0-9]+: not valid JSON | - | grow --out run --config $F/comma.json
2 | single_quotes\.json':1:[0-9]+: not valid JSON | - | grow --out run --config $F/single_quotes.json
2 | enum_unknown\.json': parameter skeletal_growth: 'axinellid' is not one of | - | grow --out run --config $F/enum_unknown.json
2 | open_bound\.json': parameter kinetic_order: '0' is not a number in \(0, 100\] | - | grow --out run --config $F/open_bound.json
2 | deep\.json'.*not valid JSON | - | grow --out run --config $F/deep.json
2 | large\.json' is larger than 1048576 bytes | - | grow --out run --config $F/large.json
2 | sphere_level_string\.json': level must be a number | - | sphere --out run --config $F/sphere_level_string.json
2 | sphere_radius_range\.json': parameter radius: '10000000' is not a number | - | sphere --out run --config $F/sphere_radius_range.json
2 | sphere_unknown\.json': unknown parameter 'wat' \('sessile sphere | - | sphere --out run --config $F/sphere_unknown.json
2 | sa\.json': unknown parameter 'noise' \('sessile grow | - | grow --out run --config $F/sa.json
# several --config files apply in order (a later one wins), then --set
0 | ^t_give +0\.3  | - | grow --config $F/a.json --config $F/b.json --print-config
0 | ^l_max +3  | - | grow --config $F/a.json --config $F/b.json --print-config
0 | ^t_give +0\.1  | - | grow --config $F/b.json --config $F/a.json --print-config
0 | ^t_give +0\.7  | - | grow --set t_give=0.7 --config $F/a.json --config $F/b.json --print-config
0 | ^noise +0\.3  | - | sphere --config $F/sa.json --config $F/sb.json --print-config
0 | ^level +2  | - | sphere --config $F/sa.json --config $F/sb.json --print-config
# cross-parameter checks: before any work, with the estimate in the message
2 | the sponge \(radius 40 cm.*does not fit the box \(38\.4 x 38\.4 x 28\.8 cm\) | - | grow --out run --set sponge_radius=40
2 | the sponge centre \(1, 19\.2\) cm puts the sponge | - | grow --out run --set sponge_x=1
2 | the sponge centre \(19\.2, 1000\) cm | - | grow --out run --set sponge_y=1000
2 | sponge_z \(7 cm\) must be below sponge_radius \(6 cm\) | - | grow --out run --set sponge_z=7
2 | vertex_insertion_threshold \(0\.5\) must exceed vertex_fusion_threshold \(0\.5\) | - | grow --out run --set vertex_insertion_threshold=0.5
2 | vertex_insertion_threshold \(0\.3\) must exceed vertex_fusion_threshold \(0\.5\) | - | grow --out run --set vertex_insertion_threshold=0.3
2 | fluid_resolution \(3\) must not exceed box_resolution \(2\) | - | grow --out run --set fluid_resolution=3
2 | the box would have [0-9.e+]+ nodes and [0-9.e+]+ tetrahedra, past 32-bit indices | - | grow --out run --set box_resolution=6 --set box_cells_x=4096
2 | the box would have 8\.08e\+08 nodes.*past 32-bit indices | - | grow --out run --set box_resolution=6
2 | the run needs about [0-9.]+ GiB \(box 1\.35e\+08 nodes, flow 1\.35e\+08 nodes\) but this machine has | - | grow --out run --set box_resolution=4 --set fluid_resolution=4 --set box_cells_x=64 --set box_cells_y=64 --set box_cells_z=64
2 | the conforming mesh would have at least 3\.6e\+08 tetrahedra.*raise conforming_size_far | - | grow --out run --set domain=conforming --set conforming_size_far=0.1
2 | the sponge .*does not fit the box | - | grow --out run --config $F/a.json --set box_cells_z=2
2 | the run needs about [0-9.]+ GiB | cpudev | grow --out run --set box_cells_x=4096
# --slices: x, y, z, or AXIS=HEIGHT inside the box, each plane once
2 | --slices: plane 'w' must start with x, y or z | - | grow --out run --slices w --print-config
2 | --slices: 'z=abc' | - | grow --out run --slices z=abc --print-config
2 | --slices: 'z=-1' is not inside the box \(z in \[0, 28\.8\] cm\) | - | grow --out run --slices z=-1 --print-config
2 | --slices: 'z=1e9' is not inside the box | - | grow --out run --slices z=1e9 --print-config
2 | --slices: 'z=nan' | - | grow --out run --slices z=nan --print-config
2 | --slices: 'z=' | - | grow --out run --slices z= --print-config
2 | --slices: 'z=0x1p3' | - | grow --out run --slices z=0x1p3 --print-config
2 | --slices: plane 'x' is given twice | - | grow --out run --slices x,x --print-config
2 | --slices: plane 'z3\.5' is given twice | - | grow --out run --slices z=3.5,z=3.5 --print-config
2 | --slices: bad plane list ',' | - | grow --out run --slices , --print-config
2 | --slices: plane '=3' must start with x, y or z | - | grow --out run --slices =3 --print-config
# --resume: only --iterations, --quiet and device options go with it; a run to resume
2 | grow: error: --resume continues a run with its own configuration | - | grow --resume x --set t_give=0.1
2 | grow: error: --resume continues a run with its own configuration | - | grow --resume x --preset crella
2 | grow: error: --resume continues a run with its own configuration | - | grow --resume x --seed 3
2 | grow: error: --resume continues a run with its own configuration | - | grow --resume x --config $F/ok.json
2 | grow: error: --resume continues a run with its own configuration | - | grow --resume x --every 2
2 | grow: error: --resume continues a run with its own configuration | - | grow --resume x --force
2 | grow: error: --resume continues a run with its own configuration | - | grow --resume x --out y
2 | grow: error: --resume continues a run with its own configuration | - | grow --resume x --slices z
2 | grow: error: --resume continues a run with its own configuration | - | grow --resume x --print-config
2 | sphere: error: --resume continues a run with its own configuration | prevrun | sphere --resume prev --seed 2
2 | sphere: error: --resume continues a run with its own configuration | prevrun | sphere --resume prev --set level=2
2 | nothing to resume in 'missing' | - | grow --resume missing
2 | nothing to resume in 'missing' | - | sphere --resume missing
2 | nothing to resume in 'a/b/c' | - | sphere --resume a/b/c --iterations 3
2 | nothing to resume in 'e': it holds no manifest\.json | emptydir | grow --resume e
2 | nothing to resume in 'e': it holds no manifest\.json | emptydir | sphere --resume e
2 | the run directory needs a name | - | sphere --resume ''
2 | 'prev' holds a run of another generator \('sphere'\), not 'grow' | prevrun | grow --resume prev
# --out: new or empty, or an earlier run only with --force
2 | 'other' is not empty and holds no sessile run | nonrun | sphere --out other
2 | 'other' is not empty and holds no sessile run | nonrun | sphere --out other --force
2 | 'other' is not empty and holds no sessile run | nonrun | grow --out other --set box_resolution=1 --iterations 1
2 | 'prev' holds an earlier run \(state completed.*add --force | prevrun | sphere --out prev --iterations 1
2 | 'prev' holds an earlier run \(state completed.*add --force | prevrun | grow --out prev --set box_resolution=1 --iterations 1
2 | cannot create the run directory.*'file': Not a directory | file | sphere --out file/run
2 | cannot create the run directory.*'file': Not a directory | file | sphere --out file
2 | the run directory needs a name | - | sphere --out ''
# stdout write errors are runtime failures (exit 1), one line
1 | cannot write | full | --help
1 | cannot write | full | help
1 | cannot write | full | version
1 | cannot write | full | grow --help
1 | cannot write | full | sphere --help
1 | cannot write | full | grow --print-config
1 | cannot write | full | sphere --print-config
# a valued option given twice is refused (the last one does not silently win);
# --set and --config repeat
2 | grow: error: --seed given twice | - | grow --seed 1 --seed 2 --print-config
2 | grow: error: --out given twice | - | grow --out a --out b --print-config
2 | --iterations given twice | - | grow --iterations 1 --iterations 2 --print-config
2 | --every given twice | - | sphere --every 1 --every 2 --print-config
2 | --resume given twice | - | sphere --resume a --resume b
2 | --preset given twice | - | grow --preset crella --preset radiate --print-config
2 | --slices given twice | - | grow --slices x --slices '' --print-config
2 | --device given twice | - | grow --device 0 --device 0 --print-config
2 | --device given twice | - | --device 0 grow --device 0 --print-config
2 | --precision given twice | - | --precision 32 grow --precision 64 --print-config
2 | render: error: -o given twice | - | render $F/prevrun/sphere/final.ply -o a.png -o b.png
2 | render: error: --out given twice | - | render $F/prevrun/sphere/final.ply -o a.png --out b.png
2 | render: error: --size given twice | - | render $F/prevrun/sphere/final.ply -o a.png --size 8x8 --size 9x9
2 | render: error: --range given twice | - | render x.exr -o a.png --range 0 1 --range 0 2
2 | render: error: -o given twice | - | render --sheet 1 -o a.png -o b.png $F/prevrun/preview.png
2 | render: error: --sheet given twice | - | render --sheet 1 --sheet 2 -o a.png $F/prevrun/preview.png
2 | sds run: error: --t-end given twice | - | sds run limb --t-end 1 --t-end 2
2 | sds run: error: --frames given twice | - | sds run limb --frames 1 --frames 2
2 | coral lsystem: error: --grammar given twice | - | coral lsystem --grammar flat --grammar flat
2 | coral lsystem: error: --seed given twice | - | coral lsystem --seed 1 --seed 1
2 | bench fluid: error: --picard given twice | - | bench fluid --picard 1 --picard 2
2 | bench fluid: error: --restart given twice | - | bench fluid --restart 3 --restart 4
2 | bench fluid: error: --repeat given twice | - | bench fluid --repeat 2 --repeat 3
2 | bench fluid: error: --repeat: '0' is not an integer in 1..20 | - | bench fluid --repeat 0
2 | bench fluid: error: --repeat: '21' is not an integer in 1..20 | - | bench fluid --repeat 21
2 | bench fluid: error: --pc: parameter fluid_pc_type: 'amg' is not one of none, jacobi, ilu0, block_jacobi, mg | - | bench fluid --pc amg
2 | bench fluid: error: --ksp: parameter fluid_ksp_type: 'cg' is not one of gmres, bicgstab | - | bench fluid --ksp cg
2 | bench fluid: error: --restart: parameter fluid_ksp_restart: '0' is not an integer in \[1, 64\] | - | bench fluid --restart 0
2 | parameter fluid_pc_type: 'ilu' is not one of none, jacobi, ilu0, block_jacobi, mg | - | bench fluid --set fluid_pc_type=ilu
0 | ^t_give +0\.2  | - | grow --set t_give=0.1 --set t_give=0.2 --print-config
# GNU --opt=value: the same checks as --opt value; a flag takes no value
2 | grow: error: --iterations: 'abc' is not an integer | - | grow --iterations=abc
2 | sphere: error: --iterations: 'abc' is not an integer | - | sphere --iterations=abc
2 | --seed: '' is not an integer | - | grow --seed= --print-config
2 | --every needs a value | - | sphere --every=
2 | sphere: error: the run directory needs a name | - | sphere --out=
2 | grow: error: --seed given twice | - | grow --seed=1 --seed 2 --print-config
2 | grow: error: --seed given twice | - | grow --seed 1 --seed=2 --print-config
2 | --out given twice | - | sphere --out=a --out=b --print-config
2 | --device given twice | - | --device=0 grow --device=0 --print-config
2 | --precision: '16' must be 32 or 64 | - | --precision=16 grow
2 | grow: error: unknown option '--bogus' | - | grow --bogus=3
2 | grow: error: unknown option '--=3' | - | grow --=3
2 | sphere: error: --force takes no value \('--force=yes'\) | - | sphere --force=yes --out x
2 | --quiet takes no value | - | sphere --quiet= --out x
2 | sessile: error: --validation takes no value | - | --validation=1 devices
2 | devices: error: --validation takes no value | - | devices --validation=1
2 | --version takes no value | - | grow --version=1
2 | render: error: --ortho takes no value \('--ortho=in\.png'\) | png | render --ortho=in.png -o a.png
2 | render: error: --quiet takes no value | png | render --sheet=1 -o a.png in.png --quiet=yes
2 | render: error: --sheet given twice | - | render --sheet=1 --sheet 2 -o a.png $F/prevrun/preview.png
2 | render: error: --size given twice | - | render $F/prevrun/sphere/final.ply --out=a.png --size=8x8 --size 9x9
2 | --range needs two values: LO HI | - | render x.exr -o a.png --range=1
2 | sds run: error: --t-end: 'inf' is not a decimal number | - | sds run limb --t-end=inf
# --progress MODE (docs/run.md "Progress"), both forms, on every command that takes it
2 | grow: error: --progress: 'bogus' is not auto, tty, lines, json or none | - | grow --progress=bogus --print-config
2 | sphere: error: --progress: 'JSON' is not auto | - | sphere --progress JSON --print-config
2 | sphere: error: --progress needs a value | - | sphere --progress
2 | sphere: error: --progress: '' is not auto | - | sphere --progress= --print-config
2 | sphere: error: --progress given twice | - | sphere --progress=json --progress json --print-config
2 | sds run: error: --progress: 'x' is not auto | - | sds run limb --progress=x
2 | coral lsystem: error: --progress: 'x' is not auto | - | coral lsystem --progress=x
2 | coral venation: error: --progress: 'x' is not auto | - | coral venation --progress=x
2 | sponge particles: error: --progress: 'x' is not auto | - | sponge particles --progress=x
2 | render: error: --progress: 'x' is not auto | - | render $F/prevrun --progress=x
2 | sweep run: error: --progress: 'x' is not auto | - | sweep run $F/nosweep --progress=x
2 | sweep run: error: --quiet takes no value | - | sweep run $F/nosweep --quiet=1
2 | sds run: error: --frames given twice | - | sds run limb --frames=1 --frames=2
2 | sds models: error: takes no arguments | - | sds models --x=1
2 | coral lsystem: error: --grammar given twice | - | coral lsystem --grammar=flat --grammar flat
2 | coral venation: error: --iterations: 'x' is not an integer | - | coral venation --iterations=x --out v
2 | sponge particles: error: --seed: 'x' is not an integer | - | sponge particles --seed=x --out p
2 | bench la: error: --size: 'x' is not an integer | - | bench la --size=x
2 | bench la: error: --no-solvers takes no value | - | bench la --no-solvers=1
2 | bench fluid: error: --picard given twice | - | bench fluid --picard=1 --picard 2
2 | bench grow: error: --iterations: 'x' is not an integer | - | bench grow --iterations=x
2 | bench render: error: --runs: '0' is not an integer | - | bench render --runs=0
2 | bench sds: error: --rock-t: 'nan' is not a decimal number | - | bench sds --rock-t=nan
2 | bench coral: error: --quick takes no value | - | bench coral --quick=1
0 | ^t_give +0\.7  | - | grow --set=t_give=0.7 --print-config
0 | ^level +2  | - | sphere --config=$F/sa.json --print-config
1 | cannot write | full | grow --version
# numbers are decimal, finite and the whole word, on every command
2 | --t-end: '0x10' is not a decimal number in \[0, 1e\+09\] | - | sds run limb --t-end 0x10
2 | --t-end: 'inf' is not a decimal number | - | sds run limb --t-end inf
2 | --t-end: 'nan' is not a decimal number | - | sds run limb --t-end nan
2 | --t-end: ' 1' is not a decimal number | - | sds run limb --t-end ' 1'
2 | --t-end: '1e' is not a decimal number | - | sds run limb --t-end 1e
2 | --units: '0x1p3' is not a decimal number | - | render $F/prevrun/sphere/final.ply -o a.png --units 0x1p3
2 | --range: '0x1 2' is not two decimal numbers | - | render x.exr -o a.png --range 0x1 2
2 | --range: '0 infinity' is not two decimal numbers | - | render x.exr -o a.png --range 0 infinity
2 | --size: ' 8x8' is not WxH | - | render $F/prevrun/sphere/final.ply -o a.png --size ' 8x8'
2 | --size: '8x\+8' is not WxH | - | render $F/prevrun/sphere/final.ply -o a.png --size 8x+8
2 | --define 'len=0x10': the value is not a finite decimal number | - | coral lsystem --define len=0x10
2 | --define 'len=inf': the value is not a finite decimal number | - | coral lsystem --define len=inf
2 | --rock-t: 'nan' is not a decimal number | - | bench sds --rock-t nan
2 | --rock-t: '0x1' is not a decimal number | - | bench sds --rock-t 0x1
# messages name the culprit and keep the reason
2 | bench fluid: error: unknown option '--bogus' | - | bench fluid --bogus
2 | bench fluid: error: unknown option '--bogus' | - | bench fluid --bogus 3
2 | --range needs two values: LO HI | - | render x.exr -o a.png --range 1
2 | --range: '1 -o' is not two decimal numbers LO < HI | - | render x.exr --range 1 -o a.png
2 | -o 'n{60}\.\.\.': File name too long | - | render $F/prevrun/sphere/final.ply -o $long.png
2 | -o 'n{60}\.\.\.': File name too long | - | render --sheet 1 -o $long.png $F/prevrun/preview.png
2 | cannot read 'n{60}\.\.\.': File name too long | - | render $long.ply -o a.png
2 | --iterations 0: a venation run grows its veins in iterations \(1 or more\) | - | coral venation --iterations 0 --out v
2 | nan_param\.lsys:4: module 'F' got a non-finite parameter | - | coral lsystem --grammar $F/nan_param.lsys --out l
2 | nan_cond\.lsys:4: the condition came out NaN | - | coral lsystem --grammar $F/nan_cond.lsys --out l
2 | nan_weight\.lsys:4: the weight came out | - | coral lsystem --grammar $F/nan_weight.lsys --out l
2 | inf_axiom\.lsys:4: module 'F' got a non-finite parameter \(inf\) | - | coral lsystem --grammar $F/inf_axiom.lsys --out l
# render's inputs: regular files only (a FIFO must not hang), never the output
2 | fifo\.png' is not a regular file | - | render --sheet 1 -o a.png $F/fifo.png
2 | fifo\.exr' is not a regular file | - | render $F/fifo.exr -o a.png
2 | fifo\.ply' is not a regular file | - | render $F/fifo.ply -o a.png
2 | --outline '.*fifo\.ply' is not a regular file | - | render $F/garbage.exr -o a.png --outline $F/fifo.ply
2 | -o 'in\.png' is the input 'in\.png' | png | render --sheet 1 -o in.png in.png
2 | -o 'link\.png' is the input 'in\.png' | png | render --sheet 2 -o link.png other.png in.png
# render RUN reads every input before it writes: a damaged one leaves no renders/
2 | final\.ply: .*the file ends | truncrun | render prev
# device options
2 | no device name contains "nosuchdevice" | - | coral venation --device nosuchdevice --out v
2 | no device name contains "nosuchdevice" | - | sponge particles --device nosuchdevice --out p
2 | no device name contains "nosuchdevice" | - | coral lsystem --device nosuchdevice --out l
2 | no device name contains "nosuchdevice" | - | --device nosuchdevice coral lsystem --out l
2 | device index 99 does not exist | - | coral lsystem --device 99 --out l
2 | no device name contains "nosuchdevice" | - | sds run limb --device nosuchdevice --out s
2 | no device name contains "nosuchdevice" | - | render $F/prevrun/sphere/final.ply -o a.png --device nosuchdevice
2 | no device name contains "nosuchdevice" | prevrun | render prev --device nosuchdevice
2 | --precision: '16' must be 32 or 64 | - | --precision 16 grow
2 | grow: error: --precision: '16' must be 32 or 64 | - | grow --precision 16
2 | --precision: '64\.0' must be 32 or 64 | - | grow --precision 64.0 --print-config
2 | --device needs an index or a name substring | - | --device '' grow
2 | grow: error: --device needs an index or a name substring | - | grow --device ''
2 | no device name contains "nosuchdevice" | - | grow --device nosuchdevice --out run --set box_resolution=1 --iterations 1
CASES
)

# The folder's listing: type, mode, size and sha256 of every entry.
# Whether folder $1 holds nothing at all (no process: most cases' folders
# stay empty, and ~350 cases of forks are most of this test's time).
empty() {
  local x
  for x in "$1"/* "$1"/.[!.]* "$1"/..?*; do
    if [ -e "$x" ] || [ -L "$x" ]; then return 1; fi
  done
  return 0
}
listing() {
  empty "$1" && return 0
  (cd "$1" && find . -mindepth 1 -printf '%y %m %s %p\n' | LC_ALL=C sort &&
    find . -type f -print0 | LC_ALL=C sort -z | xargs -0 -r sha256sum)
}

n=0 skips=0
while IFS= read -r line; do
  case "$line" in '#'* | '') continue ;; esac
  line="$line " # a case with no arguments ends in "| "
  want="${line%% | *}"; rest="${line#* | }"
  re="${rest%% | *}"; rest="${rest#* | }"
  setup="${rest%% | *}"; args="${rest#* | }"
  args="${args% }"
  n=$((n + 1))
  what="[$n] sessile $args${setup:+ ($setup)}"
  [ "$setup" = "-" ] && what="[$n] sessile $args"
  if [ "$setup" = cpudev ] && [ "$cpudev" != 1 ]; then
    echo "SKIP $what: the default device is not a CPU one"
    skips=$((skips + 1))
    continue
  fi
  d="$T/case$n"
  mkdir "$d"
  case "$setup" in
  nonrun) mkdir "$d/other" && echo "a user's notes" >"$d/other/notes.txt" ;;
  prevrun) cp -a "$F/prevrun" "$d/prev" ;;
  emptydir) mkdir "$d/e" ;;
  file) echo "not a folder" >"$d/file" ;;
  png) cp "$F/prevrun/preview.png" "$d/in.png" && cp "$d/in.png" "$d/other.png" && ln -s in.png "$d/link.png" ;;
  truncrun) cp -a "$F/prevrun" "$d/prev" && truncate -s -100 "$d/prev/sphere/final.ply" ;;
  esac
  before=$(listing "$d")
  eval "set -- $args"
  if [ "$setup" = full ]; then
    (cd "$d" && exec timeout 20 "$S" "$@" >/dev/full 2>"$T/err")
  else
    (cd "$d" && exec timeout 20 "$S" "$@" >"$T/out" 2>"$T/err")
  fi
  rc=$?
  [ "$setup" = full ] && : >"$T/out"
  after=$(listing "$d")
  why=""
  if [ "$rc" = 124 ]; then why="hung (killed after 20 s)"
  elif [ "$rc" != "$want" ]; then why="exit $rc, not $want"
  fi
  # stderr's newlines counted as wc -l counts them, by the shell (no process:
  # forks are most of this test's time)
  errtxt="" && IFS= read -r -d '' errtxt <"$T/err"
  nls="${errtxt//[!$'\n']/}"
  lines=${#nls}
  if [ "$want" = 0 ]; then
    [ -s "$T/err" ] && why="$why${why:+; }stderr not empty"
    grep -qE -- "$re" "$T/out" || why="$why${why:+; }stdout does not match /$re/"
  else
    [ "$lines" = 1 ] || why="$why${why:+; }$lines lines on stderr, not 1"
    [[ "$errtxt" == *error* ]] || why="$why${why:+; }no 'error' on stderr"
    grep -qE -- "$re" "$T/err" || why="$why${why:+; }stderr does not match /$re/"
    [ -s "$T/out" ] && why="$why${why:+; }stdout not empty"
  fi
  if [ "$before" != "$after" ]; then
    changed=$(diff <(echo "$before") <(echo "$after") | grep '^[<>]' | head -3 | tr '\n' ' ')
    why="$why${why:+; }the folder changed: $changed"
  fi
  if [ -z "$why" ]; then
    echo "PASS $what"
    passes=$((passes + 1))
  else
    echo "FAIL $what: $why"
    sed 's/^/       stderr: /' "$T/err" | head -3
    fails=$((fails + 1))
  fi
  rm -rf "$d"
done <<<"$cases"
[ "$skips" -gt 0 ] && echo "($skips skipped)"
finish
