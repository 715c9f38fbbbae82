# Table 1 and Figs. 11-13: pair update rate against shell points and voxmap voxels (data/pairs.csv).
load 'bench/plot/style.gpi'
f = data.'/pairs.csv'
device = 'ours: modelled device, '.clock_label(f)
set logscale xy

# Fig. 12 and Table 1: two panels, update rate and time per lookup against shell points.
set output out.'/fig12_shell_points.png'
set multiplot layout 1,2 title "Fig. 12 / Table 1: one pair of 36-face polytopes, voxmap of about 12,672 voxels" font ',14'
set title 'Update rate'
set xlabel 'points in the point shell'
set ylabel 'update rate (Hz, pair queries per second)'
set key inside right top
plot f using (strcol(1) eq 'shell' ? $3 : NaN):8 with linespoints ls 1 title 'ours: cpu backend, 1 thread', \
     f using (strcol(1) eq 'shell' ? $3 : NaN):11 with linespoints ls 2 title device, \
     f using (strcol(1) eq 'shell' ? $12 : NaN):13 with linespoints ls 3 dt 2 title 'paper, Table 1 (Pentium 166)'
set title 'Time per lookup'
set ylabel 'time per shell-point lookup (us)'
set key inside right center
plot f using (strcol(1) eq 'shell' ? $3 : NaN):($9/1000) with linespoints ls 1 title 'ours: cpu backend, 1 thread', \
     f using (strcol(1) eq 'shell' ? $3 : NaN):(1e6/($11*$15)) with linespoints ls 2 title 'ours: modelled device', \
     f using (strcol(1) eq 'shell' ? $12 : NaN):($14*1000) with linespoints ls 3 dt 2 title 'paper, Table 1'
unset multiplot

# Fig. 11: update rate against voxmap voxels, shell at the matching density.
set output out.'/fig11_voxels.png'
set title "Fig. 11: update rate against voxmap resolution (shell at the matching density)\n{/*0.8 the paper quotes no values of Fig. 11: not drawn}"
set xlabel 'voxels in the voxmap'
set ylabel 'update rate (Hz, pair queries per second)'
set key inside right top
plot f using (strcol(1) eq 'map' ? $4 : NaN):8 with linespoints ls 1 title 'ours: cpu backend, 1 thread', \
     f using (strcol(1) eq 'map' ? $4 : NaN):11 with linespoints ls 2 title device

# Fig. 13: the two series against shell points.
set output out.'/fig13_compared.png'
set title "Fig. 13: fixed voxmap (12,672 voxels) against a voxmap at the shell's resolution"
set xlabel 'points in the point shell'
set key inside right top
plot f using (strcol(1) eq 'shell' ? $3 : NaN):8 with linespoints ls 1 title 'ours: fixed voxmap', \
     f using (strcol(1) eq 'map' ? $3 : NaN):8 with linespoints ls 4 title 'ours: voxmap at the matching resolution', \
     f using (strcol(1) eq 'shell' ? $12 : NaN):13 with linespoints ls 3 dt 2 title 'paper: fixed voxmap (Table 1)'
