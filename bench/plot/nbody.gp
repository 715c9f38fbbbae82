# Fig. 14 (a) and (b), and the large-N extension: frame rate against objects (data/nbody.csv, data/large.csv).
load 'bench/plot/style.gpi'
f = data.'/nbody.csv'
h = data.'/nbody_mid.csv'
g = data.'/large.csv'
device_f = 'modelled device ('.clock_label(f).'), pairs only'
device_g = 'modelled device ('.clock_label(g).'), pairs only'
set logscale xy
set xrange [1.6:320]
set format x '%g'
set xlabel 'objects'
set ylabel 'update rate (frames per second)'
set key outside right top

set output out.'/fig14a_objects.png'
set title "Fig. 14(a): all pairs, bounding spheres, fast AABB (sap)\n{/*0.8 voxel 1, density 2.5%, no mid-phase; paper points: the values its text quotes}"
$paper_a << EOD
8,99.5,sphere
64,12.9,sphere
8,57.4,sap
64,19.2,sap
EOD
plot rows(f, 2, 'all') using 1:3 with linespoints ls 7 title 'ours: all pairs', \
     rows(f, 2, 'sphere') using 1:3 with linespoints ls 1 title 'ours: bounding spheres', \
     rows(f, 2, 'sap') using 1:3 with linespoints ls 4 title 'ours: fast AABB (sap)', \
     rows(h, 2, 'grid') using 1:3 with linespoints ls 4 dt 2 title 'ours: grid + mid-phase (default)', \
     rows(f, 2, 'sap') using 1:6 with linespoints ls 2 dt 3 title device_f, \
     $paper_a using 1:(strcol(3) eq 'sphere' ? $2 : NaN) with points ls 3 pt 9 title 'paper: bounding spheres', \
     $paper_a using 1:(strcol(3) eq 'sap' ? $2 : NaN) with points ls 3 pt 5 title 'paper: fast AABB'

set output out.'/fig14b_objects.png'
set title "Fig. 14(b): coherent AABB and the priority queue\n{/*0.8 voxel 1, density 2.5%, no mid-phase; paper point: 'in excess of 1000 Hz' for two objects (a lower bound)}"
$paper_b << EOD
2,1000
EOD
plot rows(f, 2, 'all') using 1:3 with linespoints ls 7 title 'ours: all pairs', \
     rows(f, 2, 'sap') using 1:3 with linespoints ls 4 title 'ours: fast AABB (sap)', \
     rows(f, 2, 'coherent') using 1:3 with linespoints ls 5 title 'ours: coherent AABB', \
     rows(f, 2, 'queue') using 1:3 with linespoints ls 6 title 'ours: priority queue', \
     rows(h, 2, 'grid') using 1:3 with linespoints ls 4 dt 2 title 'ours: grid + mid-phase (default)', \
     rows(f, 2, 'sap') using 1:6 with linespoints ls 2 dt 3 title device_f, \
     $paper_b using 1:2 with points ls 3 pt 8 ps 2.5 title 'paper: queue, > 1000 Hz'

set output out.'/large_n.png'
set title "Beyond the paper: up to 65,536 objects (voxel (64/N)^{1/3}, density 2.5%)"
set format x '10^{%T}'
set xrange [128:131072]
plot rows(g, 2, 'sap') using 1:3 with linespoints ls 4 title 'ours: sap', \
     rows(g, 2, 'tree') using 1:3 with linespoints ls 9 title 'ours: tree', \
     rows(g, 2, 'grid') using 1:3 with linespoints ls 8 title 'ours: grid (default)', \
     rows(g, 2, 'sap') using 1:6 with linespoints ls 2 dt 3 title device_g
