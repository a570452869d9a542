#!/usr/bin/env bash
# Messages for a user's slips: implausible values warn (and the run goes on),
# unknown names get a "did you mean", a misspelled TOML key is reported as unknown (not
# as the missing key it leaves), an unknown subcommand is named, descending ranges run
# and are said; the continuation's branch CSV has a row at every located special point,
# where the stability flips exactly.
#   check_messages.sh BINARY SOURCE_DIR
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
scene=$src/data/scenes/default.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"
eq() { "$bin" equilibria "$scene" --format csv "$@" >"$work/out" 2>"$work/err"; }

# --- implausible values: a warning naming the key and the slip; exit 0 --------------------
eq
check "the default scene gives no warning" "[ $? -eq 0 ] && [ ! -s '$work/err' ]"
eq --set m=33
check "m=33: exit 0, output written" "[ $? -eq 0 ] && [ -s '$work/out' ]"
check "m=33: warns grams typed as kilograms, naming m and the rotor's mass" \
  "grep -q 'warning: m = 33 kg' '$work/err' && grep -q \"rotor's mass M_r = 0.12 kg\" '$work/err' && grep -q 'grams typed as kilograms' '$work/err'"
eq --set l=18
check "l=18: warns a race radius above 1 m, millimetres typed as metres" \
  "grep -q 'l = 18 m' '$work/err' && grep -q 'millimetres typed as metres' '$work/err'"
eq --set r=0.0001 --set l=0.0005
check "l=0.5 mm: warns below 1 mm" "grep -q 'l = 0.0005 m.*below 1 mm' '$work/err'"
eq --set k=0.05
check "k=0.05: omega_n below 1 rad/s named with k" "grep -q 'omega_n = .* below 1 rad/s (k = 0.05 N/m' '$work/err'"
eq --set U=6e-4
check "U 500 times the capacity: warned with the capacity" "grep -q 'U = 0.0006 kg m .* times what the balls can cancel' '$work/err'"
eq --set U=2e-6
check "U just above the capacity (a real study): no warning" "[ ! -s '$work/err' ]"
eq --set mu=0.8
check "mu=0.8: a rolling resistance that large is warned" "grep -q 'mu = 0.8 (friction.mu)' '$work/err'"
eq --set m1=33
check "one ball: named m1 with its key" "grep -q 'm1 = 33 kg (ball\[1\].mass)' '$work/err'"
eq --set omega=90000
check "omega = 360 omega_n: rpm typed as rad/s?" "grep -q 'rpm typed as rad/s' '$work/err'"

# --- did you mean ------------------------------------------------------------------------
eq --set omgea=100
check "--set omgea: exit 2, did you mean 'omega'" "[ $? -eq 2 ] && grep -q \"did you mean 'omega'\" '$work/err'"
eq --set Mr=0.2
check "--set Mr: did you mean 'M_r'" "grep -q \"did you mean 'M_r'\" '$work/err'"
eq --set mu_k2=0.1
check "--set mu_k2: did you mean a per-ball symbol with the index" "grep -q \"did you mean 'mu_c2'\" '$work/err'"
eq --set xyz=1
check "--set xyz: no suggestion for a name far from every symbol" "[ $? -eq 2 ] && ! grep -q 'did you mean' '$work/err'"
"$bin" sweep "$scene" --param omgea --from 100 --to 200 --steps 2 -o "$work/s" 2>"$work/err"
check "sweep --param omgea: did you mean, nothing written" "[ $? -eq 2 ] && grep -q \"did you mean 'omega'\" '$work/err' && [ ! -e '$work/s' ]"
"$bin" continue "$scene" --param omgea --to 200 -o "$work/c" 2>"$work/err"
check "continue --param omgea: did you mean" "[ $? -eq 2 ] && grep -q \"did you mean 'omega'\" '$work/err'"
"$bin" map "$scene" --x omgea:100:200:3 --y mu:1e-3:1e-2:3 -o "$work/m" 2>"$work/err"
check "map --x omgea: did you mean" "[ $? -eq 2 ] && grep -q \"did you mean 'omega'\" '$work/err'"

# --- TOML keys: a misspelled key is unknown (with a suggestion), not a missing one ------------
sed 's/^stiffness/stifness/' "$scene" >"$work/stif.toml"
"$bin" equilibria "$work/stif.toml" 2>"$work/err"
check "stifness: exit 2" "[ $? -eq 2 ]"
check "stifness: reported as the unknown key with the suggestion" \
  "grep -q \"key 'rotor.stifness'\" '$work/err' && grep -q \"unknown key; did you mean 'stiffness'?\" '$work/err'"
check "stifness: not reported as a missing stiffness" "! grep -q 'missing' '$work/err'"
sed 's/^\[speed\]/[sped]/' "$scene" >"$work/sped.toml"
"$bin" equilibria "$work/sped.toml" 2>"$work/err"
check "[sped]: unknown table, did you mean 'speed'" "[ $? -eq 2 ] && grep -q \"unknown table; did you mean 'speed'? (the top level has\" '$work/err'"
sed 's/^mu = /muu = /' "$scene" >"$work/muu.toml"
"$bin" equilibria "$work/muu.toml" 2>"$work/err"
check "friction muu: the unknown key, not the law's missing mu" \
  "grep -q \"key 'friction.muu'\" '$work/err' && grep -q \"did you mean 'mu'?\" '$work/err'"
sed '/^stiffness/d' "$scene" >"$work/nok.toml"
"$bin" equilibria "$work/nok.toml" 2>"$work/err"
check "a key really missing is still reported as missing" "[ $? -eq 2 ] && grep -q \"rotor.stiffness'.*missing required key\" '$work/err'"

# --- subcommands ---------------------------------------------------------------------------
"$bin" equilibrium "$scene" 2>"$work/err"
check "unknown subcommand named with the nearest: exit 2" \
  "[ $? -eq 2 ] && grep -q \"unknown subcommand 'equilibrium'; did you mean 'equilibria'?\" '$work/err'"
"$bin" frobnicate 2>"$work/err"
check "unknown subcommand without a near one lists the subcommands" \
  "[ $? -eq 2 ] && grep -q \"unknown subcommand 'frobnicate' (subcommands: equilibria, sweep, continue, map, simulate\" '$work/err'"

# --- descending ranges: allowed, said ---------------------------------------------------------
"$bin" sweep "$scene" --param omega --from 1000 --to 100 --steps 9 --no-chart -o "$work/down" 2>"$work/err"
check "sweep --from > --to: exit 0, said" "[ $? -eq 0 ] && grep -q 'runs downward' '$work/err'"
check "descending sweep: first value 1000, last 100" \
  "[ \"\$(grep -v '^#' '$work/down/sweep_omega.csv' | awk -F, 'NR == 2 {print \$2}')\" = 1000 ] && grep -v '^#' '$work/down/sweep_omega.csv' | tail -1 | cut -d, -f2 | grep -qx 100"
"$bin" map "$scene" --x omega:600:150:6 --y mu:1e-3:1e-2:3 --no-chart --no-boundaries -o "$work/mdown" 2>"$work/err"
check "map axis FROM > TO: exit 0, said" "[ $? -eq 0 ] && grep -q -- '--x runs downward, from 600 to 150' '$work/err'"

# --- special points as rows of the branch CSV ---------------------------------------------
"$bin" continue "$scene" --set omega=50 --param omega --to 2000 --no-chart -o "$work/cont" 2>/dev/null
check "continue 50 -> 2000 exits 0" "[ $? -eq 0 ]"
check "every located special point is a row of its branch, the stability flipping exactly there" \
  "/usr/bin/python3 - '$work/cont/branch_omega.csv' '$work/cont/special_omega.csv' <<'PY'
import csv, sys
read = lambda f: list(csv.DictReader(l for l in open(f) if not l.startswith('#')))
branch, special = read(sys.argv[1]), read(sys.argv[2])
hb = [s for s in special if s['label'] == 'HB']
assert hb and any(abs(float(s['omega']) - 249.93374034470625) < 1e-9 for s in hb), 'the balanced HB at 249.93374'
for s in special:
    if s['label'] not in ('LP', 'BP', 'HB') or s['converged'] != '1':
        continue
    rows = [i for i, r in enumerate(branch) if r['branch'] == s['branch'] and r['label'] == s['label']
            and r['omega'] == s['omega']]
    assert rows, ('no row at', s['label'], s['omega'])
    before, after = branch[rows[0] - 1], branch[rows[-1] + 1]
    assert before['branch'] == s['branch'] and after['branch'] == s['branch']
    # the first row carries the side before, the last the side after
    assert branch[rows[0]]['stable'] == before['stable'] and branch[rows[-1]]['stable'] == after['stable'], s
    assert branch[rows[0]]['n_unstable'] == before['n_unstable'] and branch[rows[-1]]['n_unstable'] == after['n_unstable']
    if before['stable'] != after['stable']:
        assert len(rows) == 2, ('two rows where the stability flips', s)
for s in hb:  # the balanced Hopf point: the branch is unstable below it, stable above
    if s['family'] == 'balanced':
        rows = [r for r in branch if r['branch'] == s['branch'] and r['label'] == 'HB' and r['omega'] == s['omega']]
        assert [r['stable'] for r in rows] == ['0', '1'], rows
PY"
check "balanced rows print |q| = 0 exactly" \
  "[ -z \"\$(grep -v '^#' '$work/cont/branch_omega.csv' | awk -F, 'NR > 1 && \$10 == \"balanced\" && \$9 != 0')\" ]"

finish
