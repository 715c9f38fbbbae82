# Fixed-point widths against disagreement with exact arithmetic and against hardware cost (data/fixed.csv,
# data/cost.csv).
load 'bench/plot/style.gpi'
set output out.'/widths.png'
set multiplot layout 1,2 title 'Fixed-point widths: MF (matrix fraction bits), PF (point fraction bits)' font ',14'
set xlabel 'MF (matrix fraction bits); PF beside each point'
set format x '%g'
set title 'Disagreement with exact (double) arithmetic'
set logscale y
set ylabel 'fraction of points in another voxel'
set key inside right top
plot data.'/fixed.csv' using 1:($3 > 0 ? $3 : NaN) with linespoints ls 1 title 'shell points (half-integers)', \
     data.'/fixed.csv' using 1:($4 > 0 ? $4 : NaN) with linespoints ls 4 title 'any points', \
     data.'/fixed.csv' using 1:($4 > 0 ? $4 : NaN):(sprintf('PF %d', $2)) with labels offset 0,1 notitle
set title 'Hardware cost, voxcd\_device LANES 1 (yosys synth\_ecp5)'
unset logscale y
set format y '%g'
set ylabel 'cells'
set yrange [0:*]
set key inside left top
plot data.'/cost.csv' using 1:3 with linespoints ls 1 title 'LUT4', \
     data.'/cost.csv' using 1:4 with linespoints ls 2 title 'flip-flops', \
     data.'/cost.csv' using 1:($6*10) with linespoints ls 4 title 'CCU2C carry cells x 10', \
     data.'/cost.csv' using 1:($5*100) with linespoints ls 5 title 'MULT18X18D x 100'
unset multiplot
