// The carry unit of yosys's adders and comparators ($lcu, which techmap makes from $alu) as a Kogge-Stone parallel
// prefix: log2(WIDTH) levels of generate and propagate instead of a ripple through WIDTH bits, as an ASIC flow's
// datapath synthesis builds them. The ASIC flows (bench/timing.sh, host/sizing/asic_cost.cpp, which has this file
// compiled in) read it as `techmap -map +/techmap.v -map kogge_stone.v`: its module name sorts before techmap.v's
// _90_lcu, so techmap takes it for every $lcu. tests/host/sizing/test_timing_table.cpp proves it equal to the ripple.
(* techmap_celltype = "$lcu" *)
module _80_voxcd_lcu_kogge_stone (P, G, CI, CO);
  parameter WIDTH = 2;
  (* force_downto *) input [WIDTH-1:0] P, G;
  input CI;
  (* force_downto *) output [WIDTH-1:0] CO;
  localparam L = WIDTH > 1 ? $clog2(WIDTH) : 0;
  // Level k of the prefix in bits [k*WIDTH +: WIDTH].
  wire [(L+1)*WIDTH-1:0] p, g;
  assign p[WIDTH-1:0] = P;
  assign g[0] = G[0] | (P[0] & CI);
  genvar k, j;
  generate
    if (WIDTH > 1) begin : upper
      assign g[WIDTH-1:1] = G[WIDTH-1:1];
    end
    for (k = 0; k < L; k = k + 1) begin : level
      for (j = 0; j < WIDTH; j = j + 1) begin : position
        if (j >= (1 << k)) begin : combine
          assign g[(k+1)*WIDTH + j] = g[k*WIDTH + j] | (p[k*WIDTH + j] & g[k*WIDTH + j - (1 << k)]);
          assign p[(k+1)*WIDTH + j] = p[k*WIDTH + j] & p[k*WIDTH + j - (1 << k)];
        end else begin : pass
          assign g[(k+1)*WIDTH + j] = g[k*WIDTH + j];
          assign p[(k+1)*WIDTH + j] = p[k*WIDTH + j];
        end
      end
    end
  endgenerate
  assign CO = g[L*WIDTH +: WIDTH];
endmodule
