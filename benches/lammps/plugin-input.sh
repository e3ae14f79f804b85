#!/usr/bin/env bash
# Writes to stdout the plugin variant of in.bench: the same bed, warm-up, neighbour settings and
# floor, with two more models: `plugin` (pair_style mdrdem, MDR + Mindlin + damping with the
# parameters of `mdr-dem bench bed --law mdr`, on LAMMPS's wall/gran hertz/history floor) and
# `pluginwall` (the same pair on a fix wall/mdrdem floor of the same law, R = r).
# Usage: benches/lammps/plugin-input.sh /path/to/libmdrdem_lammps.so > in.plugin
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
plugin=$1
sed -e '/^if "${model} == hertzhist"/i if "${model} == plugin" then \&\n  "plugin load '"$plugin"'" \&\n  "pair_style mdrdem" \&\n  "pair_coeff * * youngs ${E} poisson ${nu} qc 10.0 theta 0.37 friction 0.5 damping 50.0 tangential_damping 0.5 estar 1.5e5 gstar $(2.0e5/7.0)" \&\n  "fix floor all wall/gran hertz/history 2.0e5 NULL 50.0 NULL 0.5 0 zplane 0.0 NULL"' -e '/^if "${model} == hertzhist"/i if "${model} == pluginwall" then \&\n  "plugin load '"$plugin"'" \&\n  "pair_style mdrdem" \&\n  "pair_coeff * * youngs ${E} poisson ${nu} qc 10.0 theta 0.37 friction 0.5 damping 50.0 tangential_damping 0.5 estar 1.5e5 gstar $(2.0e5/7.0)" \&\n  "fix floor all wall/mdrdem youngs ${E} poisson ${nu} qc 10.0 theta 0.37 friction 0.5 damping 50.0 tangential_damping 0.5 estar 1.5e5 gstar $(2.0e5/7.0) zplane 0.0 NULL"' \
  "$here/in.bench"
