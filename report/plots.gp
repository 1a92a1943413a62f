# Turns the laboratory's CSVs into the report's figures.
#   gnuplot -e "data='report/data'; fig='report/figures'" report/plots.gp
if (!exists("data")) data = 'report/data'
if (!exists("fig")) fig = 'report/figures'
set datafile separator ','
set terminal pngcairo size 900,600 enhanced font 'DejaVu Sans,11'
set key outside right top
set grid
set style data linespoints

# Distinct values of column 1 (integrator names) of a CSV, in order of appearance.
names(file) = system(sprintf("tail -n +2 '%s' | cut -d, -f1 | awk '!seen[$0]++' | tr '\\n' ' '", file))
positive(x) = (x > 0 ? x : NaN)
set format x '10^{%L}'
set format y '10^{%L}'

# --- stability -------------------------------------------------------------
# A value the scan could not resolve is never drawn as an ordinary point: a
# largest surviving dt below the grid (0) is drawn at the grid's bottom as ▼, one
# at the grid's top with no failure (first_failure_dt 0) as ▲.
quoted(key) = system(sprintf("awk -F, '$1 == \"%s\" { print $2 }' '%s/values.csv'", key, data))
T = quoted('stability.duration') + 0
ks = quoted('stability.feedback_ks') + 0
f = data.'/stability_boundary.csv'
at(d, k) = (abs($4 - d) < 1e-9 && abs($3 - k) < 1e-9)
resolved(d, k) = (at(d, k) && $5 > 0 && $6 > 0 ? $5 : NaN)
below(d, k) = (at(d, k) && $5 == 0 ? $9 : NaN)
above(d, k) = (at(d, k) && $6 == 0 ? $5 : NaN)
set output fig.'/stability_boundary.png'
set title sprintf('Largest surviving dt of the test chain (coarse scan), T = %g s (every grid dt at or below it survived on every start)', T)
set logscale xy
set xlabel 'chain length (particles)'
set ylabel 'largest surviving dt (s)'
set key outside right top
plot for [k=1:words(names(f))] f using 2:(strcol(1) eq word(names(f), k) ? resolved(T, ks) : NaN) \
       with linespoints lc k pt 7 title word(names(f), k), \
     for [k=1:words(names(f))] f using 2:(strcol(1) eq word(names(f), k) ? below(T, ks) : NaN) \
       with points lc k pt 11 ps 1.5 notitle, \
     for [k=1:words(names(f))] f using 2:(strcol(1) eq word(names(f), k) ? above(T, ks) : NaN) \
       with points lc k pt 9 ps 1.5 notitle, \
     NaN with points lc 'black' pt 11 ps 1.5 title '▼ fails at the grid bottom', \
     NaN with points lc 'black' pt 9 ps 1.5 title '▲ survives the grid top'

set output fig.'/stability_vs_duration.png'
set title 'Largest surviving dt (coarse scan) against the survival time T (chains of 6, 12, 24)'
set xlabel 'T (simulated s)'
set ylabel 'largest surviving dt (s)'
lens = system(sprintf("awk -F, 'NR > 1 && ($4 - %g)^2 > 1e-12 { print $2 }' '%s' | sort -nu | tr '\\n' ' '", T, f))
plot for [k=1:words(names(f))] for [l in lens] f using 4:(strcol(1) eq word(names(f), k) && $2 == l+0 && $3 == ks && $5 > 0 && $6 > 0 ? $5 : NaN) \
       with linespoints lc k pt (l+0 == 6 ? 7 : l+0 == 12 ? 5 : 13) title word(names(f), k).' cl '.l, \
     for [k=1:words(names(f))] f using 4:(strcol(1) eq word(names(f), k) && $3 == ks && $5 == 0 && strstrt(' '.lens, ' '.strcol(2).' ') > 0 ? $9 : NaN) \
       with points lc k pt 11 ps 1.5 notitle, \
     for [k=1:words(names(f))] f using 4:(strcol(1) eq word(names(f), k) && $3 == ks && $6 == 0 && strstrt(' '.lens, ' '.strcol(2).' ') > 0 ? $5 : NaN) \
       with points lc k pt 9 ps 1.5 notitle

# dt against the stiffest frequency present: ω = max(√k_s, the whip's measured
# link rate, 2√((cl−1) g / r)).
# Where one frequency governs, dt·ω is constant along a line of slope −1.
set output fig.'/stability_frequency.png'
set title sprintf("Largest surviving dt against the stiffest frequency present, T = %g s; the stiffest is\n● the feedback √k_s, ■ the whip (fastest rod rotation, measured), ▲ the static chain mode 2√((cl−1)g/r)", T)
set xlabel 'stiffest frequency ω (1/s)'
set ylabel 'largest surviving dt (s)'
omega(x) = ($12 > $13 ? ($12 > $14 ? $12 : $14) : ($13 > $14 ? $13 : $14))
ok(k) = (strcol(1) eq word(names(f), k) && abs($4 - T) < 1e-9 && $5 > 0 && $6 > 0)
plot for [k=1:words(names(f))] f using (omega(0)):(ok(k) && strcol(15) eq 'feedback' ? $5 : NaN) \
       with points lc k pt 7 ps 1.3 title word(names(f), k), \
     for [k=1:words(names(f))] f using (omega(0)):(ok(k) && strcol(15) eq 'whip' ? $5 : NaN) \
       with points lc k pt 5 ps 1.3 notitle, \
     for [k=1:words(names(f))] f using (omega(0)):(ok(k) && strcol(15) eq 'chain' ? $5 : NaN) \
       with points lc k pt 9 ps 1.3 notitle, \
     [1:1000] 1/x with lines dt 2 lc 'gray' title 'dt·ω = 1', [1:1000] 2.8/x with lines dt 3 lc 'gray' title 'dt·ω = 2.8'

# The measured map: every scanned (chain length, dt) at T, coloured by the
# fraction of starts that survived (not filled in from the boundary).
f = data.'/stability_map.csv'
list = names(f)
count = words(list)
# One dt range for every panel, so that the panels compare.
unset logscale
set xrange [*:*]
set yrange [*:*]
stats f using 5 nooutput
dtLow = STATS_min
dtHigh = STATS_max
stats f using 2 nooutput
set xrange [STATS_min/1.3:STATS_max*1.3]
set yrange [dtLow/1.2:dtHigh*1.2]
set output fig.'/stability_map.png'
set terminal pngcairo size 1200,300*((count+2)/3) enhanced font 'DejaVu Sans,10'
set multiplot layout ((count+2)/3),3 title sprintf('Measured: starts surviving T = %g s at each scanned dt (yellow: all, purple: none); above the scanned range: not run', T)
unset key
set palette defined (0 '#3b0f70', 0.5 '#de4968', 1 '#fcfdbf')
set cbrange [0:1]
set colorbox
set cblabel 'fraction of starts surviving'
set logscale xy
set xlabel 'chain length'
set ylabel 'dt'
do for [k=1:count] {
  n = word(list, k)
  set title n
  plot f using 2:(strcol(1) eq n && abs($4 - T) < 1e-9 && $3 == ks ? $5 : NaN):(strcol(1) eq n && $6 > 0 ? $7/$6 : NaN) with points pt 5 ps 0.8 palette
}
unset multiplot
unset cblabel
set autoscale xy
set terminal pngcairo size 900,600 enhanced font 'DejaVu Sans,11'
set key outside right top

# --- timing ----------------------------------------------------------------
f = data.'/timing.csv'
set output fig.'/timing_chain.png'
set title 'Cost per step of the test chain'
set xlabel 'particles'
set ylabel 'seconds per step'
plot for [n in names(data.'/timing_slopes.csv')] f using 3:(strcol(1) eq 'test-chain' && strcol(2) eq n ? positive($7) : NaN) title n

set output fig.'/timing_cloth.png'
set title 'Cost per step of the 8-way cloth'
plot for [n in names(data.'/timing_slopes.csv')] f using 3:(strcol(1) eq 'cloth-8' && strcol(2) eq n ? positive($7) : NaN) title n

# --- accuracy: work–precision ----------------------------------------------
# accuracy.csv: 1 problem, 2 integrator, 3 dt, 4 tolerance, 5 max error, 6 CPU median,
# 7 error at T, 8 energy error, 9 constraint drift, 10 CPU min, 11 CPU max, 12 survived.
f = data.'/accuracy.csv'
problems = system(sprintf("tail -n +2 '%s' | cut -d, -f1 | awk '!seen[$0]++' | tr '\\n' ' '", f))
schemes = system(sprintf("tail -n +2 '%s' | cut -d, -f2 | awk '!seen[$0]++' | tr '\\n' ' '", f))
knob(dt, tol) = (tol > 0 ? sprintf('tol %.0e', tol) : sprintf('%.2g', dt))
# The rows at both ends of each scheme's sweep on a problem (least and largest
# tolerance, else dt): only those two points are labelled, so labels never pile up.
sweepEnds(p) = sprintf("< awk -F, 'NR > 1 && $1 == \"%s\" { k = ($4 > 0 ? $4 : $3) + 0; if (!($2 in lo) || k < lo[$2]) { lo[$2] = k; lr[$2] = $0 } if (!($2 in hi) || k > hi[$2]) { hi[$2] = k; hr[$2] = $0 } } END { for (s in lr) { print lr[s]; if (hr[s] != lr[s]) print hr[s] } }' '%s'", p, f)
mine(p, scheme) = (strcol(1) eq p && strcol(2) eq scheme && positive($5) < 1e300)
do for [p in problems] {
  horizon = system(sprintf("awk -F, '$1==\"accuracy.horizon.%s\"{print $2}' '%s/values.csv'", p, data))
  set output fig.'/accuracy_'.p.'.png'
  set title sprintf("Work-precision: %s, T = %s s\nCPU median of repeats, bars min-max; each sweep's ends labelled by dt or tolerance", p, horizon) font ',10'
  set xlabel 'CPU seconds per simulated second'
  set ylabel 'max particle position error over [0, T]'
  set autoscale fix
  set offsets graph 0.02, graph 0.12, graph 0.05, graph 0.05
  # The bars' ends too are NaN outside the row's problem and scheme: autoscaling
  # counts them, and another problem's bars would widen the axis.
  plot for [k=1:words(schemes)] f using (mine(p, word(schemes, k)) ? positive($6) : NaN):(positive($5)):(mine(p, word(schemes, k)) ? $10 : NaN):(mine(p, word(schemes, k)) ? $11 : NaN) with xerrorbars lc k title word(schemes, k), \
       for [k=1:words(schemes)] sweepEnds(p) using (strcol(2) eq word(schemes, k) ? positive($6) : NaN):(positive($5)):(knob($3, $4)) with labels tc lt k font ',8' offset 0.6,0.4 left notitle
  unset offsets
  set autoscale
  set output fig.'/accuracy_order_'.p.'.png'
  set title sprintf("Max position error against dt: %s, T = %s s (fixed-step schemes)", p, horizon) font ',10'
  set xlabel 'dt (s)'
  plot for [n in schemes] f using (strcol(1) eq p && strcol(2) eq n && $4 == 0 ? $3 : NaN):(positive($5)) title n
  set output fig.'/accuracy_energy_'.p.'.png'
  set title sprintf("Energy error max |E - E_{ref}| / energy scale against dt: %s, T = %s s", p, horizon) font ',10'
  set ylabel 'energy error / scale'
  plot for [n in schemes] f using (strcol(1) eq p && strcol(2) eq n && $4 == 0 ? $3 : NaN):(positive($8)) title n
}

# --- long-time behaviour ----------------------------------------------------
f = data.'/longtime_energy.csv'
problems = system(sprintf("tail -n +2 '%s' | cut -d, -f1 | awk '!seen[$0]++' | tr '\\n' ' '", f))
schemes = system(sprintf("tail -n +2 '%s' | cut -d, -f2 | awk '!seen[$0]++' | tr '\\n' ' '", f))
unset logscale
set format x '%g'
set format y '%g'
set style data lines
do for [p in problems] {
  set output fig.'/longtime_energy_'.p.'.png'
  set title 'Energy change (E(t) - E(0)) / energy scale: '.p.' (values beyond ±0.05 run off the plot)' font ',10'
  set xlabel 't (s)'
  set ylabel '(E - E_0) / scale'
  set yrange [-0.05:0.05]
  plot for [n in schemes] f using (strcol(1) eq p && strcol(2) eq n ? $4 : NaN):5 title n
}
set yrange [*:*]
set style data linespoints
f = data.'/longtime_implicit_loss.csv'
set output fig.'/longtime_implicit_loss.png'
set title 'Implicit Euler: energy lost against dt' font ',10'
set logscale x
set format x '10^{%L}'
set xlabel 'dt (s)'
set ylabel 'fraction'
plot f using 1:4 title 'pendulum: swing energy lost per period', f using 1:5 title '6-chain: lost over the run / potential drop'
set logscale xy
set format y '10^{%L}'

# --- extremes --------------------------------------------------------------
f = data.'/extremes_stiffness.csv'
set output fig.'/extremes_stiffness.png'
set title 'Largest surviving dt of the 8-way cloth against spring stiffness (▼ fails at the window bottom, ▲ survives its top)'
set logscale xy
set xlabel 'spring k_s'
set ylabel 'largest surviving dt (s)'
plot for [k=1:words(names(f))] f using 2:(strcol(1) eq word(names(f), k) && $3 > 0 && $4 > 0 ? $3 : NaN) with linespoints lc k pt 7 title word(names(f), k), \
     for [k=1:words(names(f))] f using 2:(strcol(1) eq word(names(f), k) && $3 == 0 ? $6 : NaN) with points lc k pt 11 ps 1.5 notitle, \
     for [k=1:words(names(f))] f using 2:(strcol(1) eq word(names(f), k) && $4 == 0 ? $3 : NaN) with points lc k pt 9 ps 1.5 notitle

f = data.'/extremes_mass_ratio.csv'
set output fig.'/extremes_mass_ratio.png'
set title 'Largest surviving dt against the tip-to-link mass ratio (▲ survives the grid top; below the grid: not drawn)'
set xlabel 'tip mass / link mass'
plot for [k=1:words(names(f))] f using 2:(strcol(1) eq word(names(f), k) && $3 > 0 && $4 > 0 ? $3 : NaN) with linespoints lc k pt 7 title word(names(f), k), \
     for [k=1:words(names(f))] f using 2:(strcol(1) eq word(names(f), k) && $3 > 0 && $4 == 0 ? $3 : NaN) with points lc k pt 9 ps 1.5 notitle

f = data.'/extremes_feedback.csv'
set output fig.'/extremes_feedback.png'
set title 'Max rod stretch |C|/r against the feedback gains (RK4); line: k_d = 2√k_s'
unset logscale
set logscale x
set logscale y
set logscale cb
set format cb '10^{%L}'
set xlabel 'feedback k_s'
set ylabel 'feedback k_d'
set colorbox
set palette defined (0 '#0d0887', 0.5 '#cc4778', 1 '#f0f921')
set cbrange [*:*]
set key bottom right
plot f using (positive($1)):(positive($2)):(positive($6)) with points pt 5 ps 3 palette title 'max stretch', \
     [1:20000] 2*sqrt(x) with lines lw 2 lc 'black' title 'k_d = 2√k_s'
unset logscale cb
unset colorbox
set key outside right top

f = data.'/extremes_cg_budget.csv'
cgT = quoted('extremes.cg_budget.duration')
cgL = quoted('extremes.cg_budget.length')
set logscale xy
set xrange [0.8:200]
set xlabel 'CG iteration cap'
set ylabel 'max |C|/r over the run'
tols = system(sprintf("tail -n +2 '%s' | cut -d, -f2 | awk '!seen[$0]++' | tr '\\n' ' '", f))
do for [warm in "0 1"] {
  set output fig.'/extremes_cg_budget_'.(warm eq "1" ? 'warm' : 'cold').'.png'
  set title 'Plain CG, '.(warm eq "1" ? 'warm' : 'cold').' start, RK4 dt 0.01, '.cgL.'-chain, T = '.cgT.' s: rod stretch against the cap'."\n".'× a failed run (its stretch when it stopped); uncapped shown as a line'
  # Tolerances whose runs coincide (the cap binds before any of them) are
  # drawn as open symbols of decreasing size, so each stays visible.
  plot for [k=1:words(tols)] f using ($3 > 0 ? $3 : NaN):(strcol(1) eq warm && strcol(2) eq word(tols, k) ? positive($6) : NaN) with linespoints lc k pt (2 * k + 2) ps (2.6 - 0.35 * k) title 'tol '.word(tols, k), \
       for [k=1:words(tols)] f using ($3 > 0 && $4 == 0 ? $3 : NaN):(strcol(1) eq warm && strcol(2) eq word(tols, k) ? positive($6) : NaN) with points lc k pt 2 ps 2.5 notitle, \
       for [k=1:words(tols)] f using (0.8):(strcol(1) eq warm && strcol(2) eq word(tols, k) && $3 == 0 ? positive($6) : NaN):(199.2):(0) with vectors nohead dt 2 lc k notitle
}
unset xrange

# --- claims ----------------------------------------------------------------
f = data.'/claims_cg_iterations.csv'
set output fig.'/claims_cg_iterations.png'
set title 'CG iterations per solve against the number of constraints (test chain, RK4)'
set xlabel 'constraints m'
set ylabel 'iterations per solve'
plot f using 1:(positive($2)) title 'plain CG, cold start', f using 1:(positive($3)) title 'Jacobi-preconditioned CG, warm start', \
     [*:*] x with lines dt 2 lc 'gray' title 'iterations = m'

# --- small steps (XPBD) -----------------------------------------------------
# small_steps.csv: scene,family,split,budget,substeps,iterations,dt,cpu,constraint_error,energy_loss,position_error,failure
f = data.'/small_steps.csv'
set logscale xy
set xlabel 'budget n = substeps × iterations per 1/60 s step'
set key outside right top
do for [scene in "chain80 stiff-cloth hair"] {
  set output fig.'/small_steps_'.scene.'.png'
  set multiplot layout 1,2 title 'XPBD at a fixed budget on '.scene.': n substeps of 1 pass (nx1), √n×√n, 1 substep of n passes (1xn)'
  set ylabel 'worst relative constraint violation over the run'
  plot for [s in "nx1 sqrt 1xn"] f using 4:(strcol(1) eq scene && strcol(2) eq 'xpbd' && strcol(3) eq s ? positive($9) : NaN) title s
  set ylabel 'position error at T / scene diagonal'
  plot for [s in "nx1 sqrt 1xn"] f using 4:(strcol(1) eq scene && strcol(2) eq 'xpbd' && strcol(3) eq s ? positive($11) : NaN) title s
  unset multiplot
}

# Every run of every family: position error against CPU time per simulated second.
set output fig.'/small_steps_cost.png'
set multiplot layout 1,3 title 'Position error at T against CPU time per simulated second (xpbd at 1/60 s over its budget; RK4 and implicit Euler over dt)'
set xlabel 'CPU s per simulated s'
set ylabel 'position error / diagonal'
set key inside bottom left
do for [scene in "chain80 stiff-cloth hair"] {
  set title scene
  plot for [fam in "xpbd implicit-euler rk4"] f using (strcol(1) eq scene && strcol(2) eq fam && strcol(12) eq 'none' ? positive($8) : NaN):(positive($11)) with points pt 7 title fam
}
unset multiplot
unset title

# The stiff cloth at 60 Hz: frame time against substeps, beside RK4 and the 16 ms budget.
f = data.'/small_steps_cloth.csv'
set output fig.'/small_steps_cloth.png'
unset logscale xy
set format x '%g'
set format y '%g'
set key inside top left
set xlabel 'xpbd substeps per 1/60 s frame (1 pass each)'
set ylabel 'CPU ms per frame (median)'
set y2label 'worst spring strain over the run (%)'
set y2tics
rk4 = real(system(sprintf("awk -F, '$1==\"rk4-step\" {print $3}' '%s'", f)))
plot f using 2:(strcol(1) eq 'xpbd' ? $3 : NaN) title 'xpbd frame (ms)', \
     f using 2:(strcol(1) eq 'xpbd' ? 100*$6 : NaN) axes x1y2 title 'worst strain (%)', \
     f using 2:(strcol(1) eq 'xpbd-lines' ? $3 : NaN) with linespoints pt 5 title 'xpbd, hanging lines solved: frame (ms)', \
     f using 2:(strcol(1) eq 'xpbd-lines' ? 100*$6 : NaN) axes x1y2 with linespoints pt 4 title 'hanging lines solved: worst strain (%)', \
     16 with lines dt 2 lc 'black' title '16 ms frame budget', \
     5*rk4 with lines dt 3 lc 'red' title 'five RK4 steps', \
     3 axes x1y2 with lines dt 4 lc 'blue' title '3 % strain'
unset y2tics
unset y2label

# --- cost of accuracy against size -----------------------------------------
# The cheapest certified pick's CPU time per simulated second against the
# particle count, per family and budget (cost_vs_size.csv), with its spread.
f = data.'/cost_vs_size.csv'
set output fig.'/cost_vs_size.png'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set key inside top left
set xlabel 'particles'
set ylabel 'CPU s per simulated s of the cheapest pick'
set title sprintf('The cost of accuracy against size (first %g s from release)', quoted('cost.size_horizon') + 0)
plot for [fam in "chain cloth"] for [b in "0.01 0.0001"] \
       f using (strcol(1) eq fam && abs($6 - real(b)) < 1e-12 ? $3 : NaN):12:13:14 with yerrorlines \
       title fam.', budget '.b
unset title
