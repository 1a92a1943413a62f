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
f = data.'/stability_boundary.csv'
set output fig.'/stability_boundary.png'
set title 'Largest dt at which the test chain survives T'
set logscale xy
set xlabel 'chain length (particles)'
set ylabel 'max stable dt (s)'
plot for [n in names(f)] f using 2:(strcol(1) eq n ? positive($4) : NaN) title n

set output fig.'/stability_boundary_dimensionless.png'
set title 'Stability boundary in the dimensionless step dt·√(g/r)'
set ylabel 'max stable dt·√(g/r)'
plot for [n in names(f)] f using 2:(strcol(1) eq n ? positive($5) : NaN) title n

f = data.'/stability_vs_duration.csv'
set output fig.'/stability_vs_duration.png'
set title 'How the boundary moves with the survival time T'
set xlabel 'T (simulated s)'
set ylabel 'max stable dt (s)'
plot for [n in names(f)] f using 3:(strcol(1) eq n ? positive($4) : NaN) title n

# Heat maps: survived (1) or exploded (0) over chain length × dt, one panel per integrator.
f = data.'/stability_map.csv'
list = names(f)
count = words(list)
set output fig.'/stability_map.png'
set terminal pngcairo size 1200,300*((count+2)/3) enhanced font 'DejaVu Sans,10'
set multiplot layout ((count+2)/3),3 title 'Test chain survives T? (yellow: yes)'
unset key
set palette defined (0 '#3b0f70', 1 '#fcfdbf')
set cbrange [0:1]
unset colorbox
set logscale xy
set xlabel 'chain length'
set ylabel 'dt'
do for [k=1:count] {
  n = word(list, k)
  set title n
  plot f using 2:(strcol(1) eq n ? $3 : NaN):(strcol(1) eq n ? $5 : NaN) with points pt 5 ps 2.2 palette
}
unset multiplot
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
f = data.'/accuracy.csv'
problems = system(sprintf("tail -n +2 '%s' | cut -d, -f1 | awk '!seen[$0]++' | tr '\\n' ' '", f))
do for [p in problems] {
  set output fig.'/accuracy_'.p.'.png'
  set title 'Work-precision: '.p
  set xlabel 'CPU seconds per simulated second'
  set ylabel 'max position error at T'
  plot for [n in names(data.'/timing_slopes.csv')] f using (strcol(1) eq p && strcol(2) eq n ? positive($6) : NaN):(positive($5)) title n
  set output fig.'/accuracy_order_'.p.'.png'
  set title 'Error against dt: '.p
  set xlabel 'dt (s)'
  plot for [n in names(data.'/timing_slopes.csv')] f using (strcol(1) eq p && strcol(2) eq n && $4 == 0 ? $3 : NaN):(positive($5)) title n
}

# --- extremes --------------------------------------------------------------
f = data.'/extremes_stiffness.csv'
set output fig.'/extremes_stiffness.png'
set title 'Largest stable dt of the 8-way cloth against spring stiffness'
set xlabel 'spring k_s'
set ylabel 'max stable dt (s)'
plot for [n in names(f)] f using 2:(strcol(1) eq n ? positive($3) : NaN) title n

f = data.'/extremes_mass_ratio.csv'
set output fig.'/extremes_mass_ratio.png'
set title 'Largest stable dt against the tip-to-link mass ratio'
set xlabel 'tip mass / link mass'
plot for [n in names(f)] f using 2:(strcol(1) eq n ? positive($3) : NaN) title n

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
plot f using (positive($1)):(positive($2)):(positive($5)) with points pt 5 ps 3 palette title 'max stretch', \
     [1:20000] 2*sqrt(x) with lines lw 2 lc 'black' title 'k_d = 2√k_s'
unset logscale cb
unset colorbox
set key outside right top

f = data.'/extremes_cg_budget.csv'
set logscale xy
set xlabel 'CG iteration cap (uncapped drawn at 100)'
set ylabel 'max |C|/r over the run (exploded runs end at their explosion)'
tols = system(sprintf("tail -n +2 '%s' | cut -d, -f2 | awk '!seen[$0]++' | tr '\\n' ' '", f))
do for [warm in "0 1"] {
  set output fig.'/extremes_cg_budget_'.(warm eq "1" ? 'warm' : 'cold').'.png'
  set title 'A starved solver, plain CG, '.(warm eq "1" ? 'warm' : 'cold').' start: rod stretch against the iteration cap'
  plot for [t in tols] f using ($3 > 0 ? $3 : 100):(strcol(1) eq warm && strcol(2) eq t ? positive($5) : NaN) title 'tol '.t
}

# --- claims ----------------------------------------------------------------
f = data.'/claims_cg_iterations.csv'
set output fig.'/claims_cg_iterations.png'
set title 'CG iterations per solve against the number of constraints (test chain)'
set xlabel 'constraints m'
set ylabel 'iterations per solve'
plot f using 1:(positive($2)) title 'plain CG, cold start', f using 1:(positive($3)) title 'default solver'

# --- small steps (XPBD) -----------------------------------------------------
# small_steps.csv: scene,family,split,budget,substeps,iterations,dt,cpu,constraint_error,energy_loss,position_error,exploded
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
  plot for [fam in "xpbd implicit-euler rk4"] f using (strcol(1) eq scene && strcol(2) eq fam && $12 == 0 ? positive($8) : NaN):(positive($11)) with points pt 7 title fam
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
     16 with lines dt 2 lc 'black' title '16 ms frame budget', \
     5*rk4 with lines dt 3 lc 'red' title 'five RK4 steps', \
     3 axes x1y2 with lines dt 4 lc 'blue' title '3 % strain'
unset y2tics
unset y2label
