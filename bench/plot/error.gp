# Speed against error per voxel size (data/error.csv): rate and error summaries, and the distributions.
load 'bench/plot/style.gpi'
f = data.'/error.csv'
device = 'device '.clock_label(f).', A in B'
set format x '%g'
set logscale x
set xlabel 'voxel size (world units; the polytope is about 2 across)'
vmin = 1e30
vmax = 0
do for [i=1:words(voxels)] { v = word(voxels, i) + 0; vmin = v < vmin ? v : vmin; vmax = v > vmax ? v : vmax }
set xrange [vmax * 1.3:vmin / 1.3]
# A tic at each voxel size measured.
xt = ''
do for [i=1:words(voxels)] { xt = xt.sprintf('"%s" %s,', word(voxels, i), word(voxels, i)) }
eval('set xtics ('.xt[1:strlen(xt)-1].')')

set output out.'/error_speed.png'
set multiplot layout 1,2 title 'Speed against error: one pair of 36-face polytopes, one direction (A in B) and both' font ',14'
set title 'Speed'
set logscale y
set format y '10^{%T}'
set ylabel 'pair update rate (Hz)'
set key inside left bottom
plot rows2(f, 1, 'summary', 3, '0') using 2:5 with linespoints ls 1 title 'cpu, A in B', \
     rows2(f, 1, 'summary', 3, '1') using 2:5 with linespoints ls 1 dt 2 title 'cpu, both', \
     rows2(f, 1, 'summary', 3, '0') using 2:7 with linespoints ls 2 title device, \
     rows2(f, 1, 'summary', 3, '1') using 2:7 with linespoints ls 2 dt 2 title 'device, both', \
     rows2(f, 1, 'summary', 3, '0') using 2:(1e6/$14) with lines ls 4 title 'FCL GJK (convex)', \
     rows2(f, 1, 'summary', 3, '0') using 2:(1e6/$15) with lines ls 5 title 'Bullet GJK/EPA (convex)'
set title 'Worst error (a kind with no pose is not drawn)'
set ylabel 'world units'
set key inside right top
plot rows2(f, 1, 'summary', 3, '0') using 2:($10*$2) with linespoints ls 3 title 'missed: deepest, A in B', \
     rows2(f, 1, 'summary', 3, '1') using 2:($10*$2) with linespoints ls 3 dt 2 title 'missed: deepest, both', \
     rows2(f, 1, 'summary', 3, '0') using 2:($11*$2) with linespoints ls 6 title 'false: farthest, A in B', \
     rows2(f, 1, 'summary', 3, '1') using 2:($11*$2) with linespoints ls 6 dt 2 title 'false: farthest, both', \
     rows2(f, 1, 'summary', 3, '0') using 2:2 with lines ls 7 dt 3 title 'one voxel'
unset multiplot

set output out.'/error_distribution.png'
unset logscale
set xrange [0:*] noreverse
set xtics autofreq
set format x '%g'
set format y '%g'
set multiplot layout 1,2 title 'Distribution of the errors (A in B), in voxels of each size' font ',14'
set title 'Missed contacts: penetration depth'
set xlabel 'penetration depth of a missed pose (voxels)'
set ylabel 'fraction of missed poses at or below'
set yrange [0:1.02]
set key inside right bottom
undefine STATS_*
stats f using (strcol(1) eq 'missed' && $3 == 0 ? $4 : NaN) nooutput
if (!exists("STATS_records") || STATS_records == 0) {
  set label 1 "no missed contacts:\nevery pose that touches by exact geometry\nhas a hit at every voxel size" at graph 0.5, 0.5 center font ',13'
  set xrange [0:1]
  unset key
  plot NaN notitle
  set key inside right bottom
  unset label 1
  set xrange [0:*]
} else {
  plot for [i=1:words(voxels)] f using (strcol(1) eq 'missed' && $2 == word(voxels, i) + 0 && $3 == 0 ? $4 : NaN):(1) \
       smooth cnormal with steps ls (i + 3) title 'voxel '.word(voxels, i)
}
set title 'False contacts: separation'
set xlabel 'separation of a false pose (voxels)'
set ylabel 'fraction of false poses at or below'
plot for [i=1:words(voxels)] f using (strcol(1) eq 'false' && $2 == word(voxels, i) + 0 && $3 == 0 ? $4 : NaN):(1) \
     smooth cnormal with steps ls (i + 3) title 'voxel '.word(voxels, i)
unset multiplot
