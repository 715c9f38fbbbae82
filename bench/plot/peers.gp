# Broadphases against Bullet and FCL on the same scenes (data/peers_bp.csv from bench_broadphase --csv).
load 'bench/plot/style.gpi'
f = data.'/peers_bp.csv'
set output out.'/peers_broadphase.png'
set title "Broadphase time per frame against Bullet and FCL\n{/*0.8 box overlap, equal spheres at 2.5% density, one thread}"
set logscale xy
set xlabel 'objects'
set ylabel 'time per frame (us)'
set key outside right top
plot rows(f, 2, 'sap') using 1:5 with linespoints ls 4 title 'ours: sap', \
     rows(f, 2, 'coherent') using 1:5 with linespoints ls 5 title 'ours: coherent', \
     rows(f, 2, 'tree') using 1:5 with linespoints ls 9 title 'ours: tree', \
     rows(f, 2, 'grid') using 1:5 with linespoints ls 8 title 'ours: grid', \
     rows(f, 2, 'Bullet axis sweep') using 1:5 with linespoints ls 1 dt 2 title 'Bullet axis sweep', \
     rows(f, 2, 'Bullet dbvt') using 1:5 with linespoints ls 2 dt 2 title 'Bullet dbvt', \
     rows(f, 2, 'FCL dynamic tree') using 1:5 with linespoints ls 3 dt 2 title 'FCL dynamic tree', \
     rows(f, 2, 'FCL SaP') using 1:5 with linespoints ls 7 dt 2 title 'FCL SaP'
