// voxcd_axi_regs: the AXI top's register file and memory port (voxcd_axi; docs/hardware.md, "The AXI top").
//
// An AXI4-Lite slave (AxilDw = 32 or 64 data bits, one outstanding read and one outstanding write): the registers
// of the SystemC address map (ref/address_map.h) at 0x0000 .. 0x0fff, and the shell and voxmap memory windows,
// whose writes it assembles into the device's memory write port (voxcd_axi's header has the rules and responses).
// It keeps RUN (run_o: the job stream opens) and the words loaded in each memory (shell_words_o, map_words_o);
// STATUS, STAGED, RESULT_COUNT and the totals come from the job receiver (voxcd_axi_jobs), the record sender
// (voxcd_axi_records) and the device. Latency: a read's data and a write's response the cycle after the request
// (a write: after both its address and its data).
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
module voxcd_axi_regs #(
  parameter int unsigned PW      = voxcd_arch_pkg::PW,
  parameter int unsigned PF      = voxcd_arch_pkg::PF,
  parameter int unsigned MW      = voxcd_arch_pkg::MW,
  parameter int unsigned MF      = voxcd_arch_pkg::MF,
  parameter int unsigned TW      = voxcd_arch_pkg::TW,
  parameter int unsigned DW      = voxcd_arch_pkg::DW,
  parameter int unsigned MEMW    = voxcd_arch_pkg::MEMW,
  parameter int unsigned MAW     = voxcd_arch_pkg::MAW,
  parameter int unsigned SB      = voxcd_arch_pkg::SB,
  parameter int unsigned WB      = voxcd_arch_pkg::WB,
  parameter int unsigned Depth   = voxcd_arch_pkg::Depth,
  parameter int unsigned BL      = voxcd_arch_pkg::BL,
  parameter int unsigned LANES   = voxcd_arch_pkg::LANES,
  parameter int unsigned SAW     = voxcd_arch_pkg::SAW,
  parameter int unsigned TAGW    = voxcd_arch_pkg::TAGW,
  parameter int unsigned BANKS   = voxcd_arch_pkg::BANKS,
  parameter int unsigned AxilDw  = 32,     // AXI4-Lite data bits: 32 or 64
  parameter int unsigned ClockPs = 10000   // the CLOCK_PS register: the clock period in picoseconds
) (
  input  logic                          clk_i,
  input  logic                          rst_ni,
  // AXI4-Lite slave
  input  logic                          s_axil_awvalid_i,
  output logic                          s_axil_awready_o,
  input  logic [31:0]                   s_axil_awaddr_i,
  input  logic [2:0]                    s_axil_awprot_i,   // ignored
  input  logic                          s_axil_wvalid_i,
  output logic                          s_axil_wready_o,
  input  logic [AxilDw-1:0]             s_axil_wdata_i,
  input  logic [AxilDw/8-1:0]           s_axil_wstrb_i,
  output logic                          s_axil_bvalid_o,
  input  logic                          s_axil_bready_i,
  output logic [1:0]                    s_axil_bresp_o,
  input  logic                          s_axil_arvalid_i,
  output logic                          s_axil_arready_o,
  input  logic [31:0]                   s_axil_araddr_i,
  input  logic [2:0]                    s_axil_arprot_i,   // ignored
  output logic                          s_axil_rvalid_o,
  input  logic                          s_axil_rready_i,
  output logic [AxilDw-1:0]             s_axil_rdata_o,
  output logic [1:0]                    s_axil_rresp_o,
  // The device's memory write port
  output logic                          shell_we_o,
  output logic [SAW-1:0]                shell_waddr_o,
  output logic [3*PW-1:0]               shell_wdata_o,
  output logic                          map_we_o,
  output logic [MAW-1:0]                map_waddr_o,
  output logic [MEMW-1:0]               map_wdata_o,
  // RUN has been written; the words loaded in each memory
  output logic                          run_o,
  output logic [63:0]                   shell_words_o,
  output logic [63:0]                   map_words_o,
  // What the registers show: the device busy, a descriptor received, one checked, a frame being received, a record
  // waiting, the totals, the descriptors dropped and the device's bank conflict cycles
  input  logic                          dev_busy_i,
  input  logic                          desc_full_i,
  input  logic                          checked_i,
  input  logic                          receiving_i,
  input  logic                          rec_valid_i,
  input  logic [63:0]                   jobs_done_i,
  input  logic [63:0]                   hits_i,
  input  logic [63:0]                   points_i,
  input  logic [63:0]                   cycles_i,
  input  logic [63:0]                   stalls_i,
  input  logic [63:0]                   dropped_i,
  input  logic [voxcd_arch_pkg::CW-1:0] conflicts_i
);

  localparam int unsigned AlignW   = $clog2(AxilDw / 8);

  localparam logic [1:0] RespOkay   = 2'b00;
  localparam logic [1:0] RespSlverr = 2'b10;
  localparam logic [1:0] RespDecerr = 2'b11;

  // The address map (ref/address_map.h).
  localparam logic [31:0] RegSize    = 32'h0000_1000;
  localparam logic [31:0] ShellBase  = 32'h1000_0000;
  localparam logic [31:0] MapBase    = 32'h2000_0000;
  localparam logic [63:0] ShellBytes = 64'd16 << SAW;
  localparam logic [63:0] MapBytes   = 64'd8 << MAW;
  localparam logic [63:0] DeviceId   = 64'h766f_7863_6400_0001;
  localparam logic [11:0] RegId = 12'h000, RegConfig0 = 12'h008, RegConfig1 = 12'h010, RegClockPs = 12'h018,
                          RegStatus = 12'h020, RegStaged = 12'h028, RegResultCount = 12'h030, RegRun = 12'h038,
                          RegJobsDone = 12'h040, RegHits = 12'h048, RegPoints = 12'h050, RegCycles = 12'h058,
                          RegStalls = 12'h060, RegShellWords = 12'h068, RegMapWords = 12'h070,
                          RegDropped = 12'h078, RegConflicts = 12'h080;
  localparam logic [63:0] Config0 = {8'(LANES), 8'(MEMW), 8'(DW), 8'(TW), 8'(MF), 8'(MW), 8'(PF), 8'(PW)};
  localparam logic [63:0] Config1 = {8'(BL), 8'(Depth), 8'(BANKS), 8'(WB), 8'(SB), 8'(TAGW), 8'(MAW), 8'(SAW)};

  // Whether v, read as signed, fits `w` (1..64) bits signed: the bits from w-1 up all equal.
  function automatic logic fits_signed64(input logic [63:0] v, input int unsigned w);
    logic [63:0] upper;
    upper         = $signed(v) >>> (w - 1);
    fits_signed64 = upper == '0 || upper == '1;
  endfunction

  logic [63:0] shell_words_q, map_words_q;
  logic        run_q;

  // ---- AXI4-Lite: registers ----
  logic        busy;
  logic [63:0] status;
  assign busy   = dev_busy_i || desc_full_i || checked_i || receiving_i || rec_valid_i;
  assign status = {60'd0, 1'b0, desc_full_i || checked_i, rec_valid_i, busy};  // fault, staged, results, busy

  // Whether byte address a is in the window [base, base + size).
  function automatic logic in_window(input logic [31:0] a, input logic [31:0] base, input logic [63:0] size);
    logic [31:0] off;
    off = a - base;
    in_window = a >= base && {32'd0, off} < size;
  endfunction

  // ---- AXI4-Lite: reads (one outstanding) ----
  logic              rvalid_q;
  logic [AxilDw-1:0] rdata_q, rdata_d;
  logic [1:0]        rresp_q, rresp_d;

  always_comb begin
    logic [63:0] v;
    logic [1:0]  kind;
    // The register at the offset; kind: 0 readable, 1 write-only (RUN), 2 none.
    kind = 2'd0;
    case ({s_axil_araddr_i[11:3], 3'b000})
      RegId:          v = DeviceId;
      RegConfig0:     v = Config0;
      RegConfig1:     v = Config1;
      RegClockPs:     v = 64'(ClockPs);
      RegStatus:      v = status;
      RegStaged:      v = 64'(desc_full_i) + 64'(checked_i);
      RegResultCount: v = 64'(rec_valid_i);
      RegJobsDone:    v = jobs_done_i;
      RegHits:        v = hits_i;
      RegPoints:      v = points_i;
      RegCycles:      v = cycles_i;
      RegStalls:      v = stalls_i;
      RegShellWords:  v = shell_words_q;
      RegMapWords:    v = map_words_q;
      RegDropped:     v = dropped_i;
      RegConflicts:   v = 64'(conflicts_i);
      RegRun:         begin v = '0; kind = 2'd1; end
      default:        begin v = '0; kind = 2'd2; end
    endcase
    rdata_d = AxilDw'(AxilDw == 64 ? v : (s_axil_araddr_i[2] ? v >> 32 : v));
    if (s_axil_araddr_i < RegSize) begin
      rresp_d = kind == 2'd0 ? RespOkay : (kind == 2'd1 ? RespSlverr : RespDecerr);
      if (AlignW'(s_axil_araddr_i) != '0) rresp_d = RespSlverr;
    end else if (in_window(s_axil_araddr_i, ShellBase, ShellBytes) || in_window(s_axil_araddr_i, MapBase, MapBytes)) begin
      rresp_d = RespSlverr;  // the memories are write-only
    end else begin
      rresp_d = RespDecerr;
    end
    if (rresp_d != RespOkay) rdata_d = '0;
  end

  assign s_axil_arready_o = !rvalid_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rvalid_q <= 1'b0;
      rdata_q  <= '0;
      rresp_q  <= RespOkay;
    end else if (s_axil_arvalid_i && s_axil_arready_o) begin
      rvalid_q <= 1'b1;
      rdata_q  <= rdata_d;
      rresp_q  <= rresp_d;
    end else if (s_axil_rready_i) begin
      rvalid_q <= 1'b0;
    end
  end

  assign s_axil_rvalid_o = rvalid_q;
  assign s_axil_rdata_o  = rdata_q;
  assign s_axil_rresp_o  = rresp_q;

  // ---- AXI4-Lite: writes (address and data taken in either order, then one response) ----
  logic                aw_full_q, w_full_q, bvalid_q;
  logic [31:0]         awaddr_q;
  logic [AxilDw-1:0]   wdata_q;
  logic [AxilDw/8-1:0] wstrb_q;
  logic [1:0]          bresp_q, bresp_d;
  logic                do_write;
  // Parts of a memory word written before the write that commits it.
  logic [SAW-1:0]      sk_q;        // the shell word they belong to
  logic [1:0]          shas_q;      // x, y written
  logic [PW-1:0]       sx_q, sy_q;
  logic [MAW-1:0]      mk_q;
  logic                mhas_q;      // low half written (AxilDw = 32)
  logic [31:0]         mlo_q;
  // Next values from this write.
  logic [1:0]          shas_d;
  logic [PW-1:0]       sx_d, sy_d;
  logic [SAW-1:0]      sk_d;
  logic                mhas_d;
  logic [MAW-1:0]      mk_d;
  logic [31:0]         mlo_d;
  logic                run_d;

  assign s_axil_awready_o = !aw_full_q && !bvalid_q;
  assign s_axil_wready_o  = !w_full_q && !bvalid_q;
  assign do_write         = aw_full_q && w_full_q && !bvalid_q;

  // The memory word the pending write addresses (when it is in that memory's window).
  logic [31:0]    shell_off, map_off;
  logic [SAW-1:0] shell_k;
  logic [MAW-1:0] map_k;
  assign shell_off = awaddr_q - ShellBase;
  assign map_off   = awaddr_q - MapBase;
  assign shell_k   = SAW'(shell_off >> 4);
  assign map_k     = MAW'(map_off >> 3);

  // A write's effect: its response, and the memory write it commits (if any).
  always_comb begin
    logic [31:0] a;
    logic [3:0]  b;         // byte offset in a shell word, or in a voxmap word (b[2:0])
    logic [31:0] lo, hi;    // the write's two 32-bit halves (hi only with AxilDw = 64)
    logic [63:0] word;
    a           = awaddr_q;
    lo          = wdata_q[31:0];
    hi          = AxilDw == 64 ? 32'(wdata_q >> 32) : 32'd0;
    b           = a[3:0];
    word        = 64'd0;
    bresp_d     = RespOkay;
    run_d       = 1'b0;
    shell_we_o    = 1'b0;
    map_we_o      = 1'b0;
    shell_waddr_o = sk_q;
    shell_wdata_o = {sy_q, sy_q, sx_q};  // with shell_we_o low: any value
    map_waddr_o   = mk_q;
    map_wdata_o   = '0;
    shas_d      = shas_q;
    sk_d        = sk_q;
    sx_d        = sx_q;
    sy_d        = sy_q;
    mhas_d      = mhas_q;
    mk_d        = mk_q;
    mlo_d       = mlo_q;
    if (AlignW'(a) != '0 || wstrb_q != '1) begin
      bresp_d = RespSlverr;  // an unaligned address or a partial WSTRB: the write changes nothing
    end else if (a < RegSize) begin
      if ({a[11:3], 3'b000} == RegRun) run_d = 1'b1;
      else bresp_d = {a[11:3], 3'b000} <= RegConflicts ? RespSlverr : RespDecerr;  // read-only, or no register
    end else if (in_window(a, ShellBase, ShellBytes)) begin
      if (busy) bresp_d = RespSlverr;
      else if (b == 4'd0 || b == 4'd4) begin
        // x (and y with AxilDw = 64), or y.
        if (b == 4'd0 && !fits_signed64(64'($signed(lo)), PW)) bresp_d = RespSlverr;
        if ((b == 4'd4 || AxilDw == 64) && !fits_signed64(64'($signed(b == 4'd4 ? lo : hi)), PW))
          bresp_d = RespSlverr;
        if (bresp_d == RespOkay) begin
          if (shell_k != sk_q) shas_d = 2'b00;
          sk_d = shell_k;
          if (b == 4'd0) begin
            sx_d      = PW'(lo);
            shas_d[0] = 1'b1;
          end
          if (b == 4'd4 || AxilDw == 64) begin
            sy_d      = PW'(b == 4'd4 ? lo : hi);
            shas_d[1] = 1'b1;
          end
        end
      end else if (b == 4'd8) begin
        // z commits the word (with AxilDw = 64 the reserved bytes 12..15 come with it and must be zero).
        if (!fits_signed64(64'($signed(lo)), PW) || hi != '0 || shas_q != 2'b11 || shell_k != sk_q)
          bresp_d = RespSlverr;
        else begin
          shell_we_o    = 1'b1;
          shell_wdata_o = {PW'(lo), sy_q, sx_q};
          shas_d      = 2'b00;
        end
      end else if (lo != '0) begin
        bresp_d = RespSlverr;  // bytes 12..15 are reserved
      end
    end else if (in_window(a, MapBase, MapBytes)) begin
      word  = AxilDw == 64 ? {hi, lo} : {lo, mlo_q};
      if (busy) bresp_d = RespSlverr;
      else if (AxilDw == 32 && b[2] == 1'b0) begin
        if (MEMW < 32 && (lo >> MEMW) != '0) bresp_d = RespSlverr;
        else begin
          mhas_d = 1'b1;
          mk_d   = map_k;
          mlo_d  = lo;
        end
      end else begin
        if ((MEMW < 64 && (word >> MEMW) != '0) || (AxilDw == 32 && (!mhas_q || map_k != mk_q)))
          bresp_d = RespSlverr;
        else begin
          map_we_o    = 1'b1;
          map_waddr_o = map_k;
          map_wdata_o = MEMW'(word);
          mhas_d    = 1'b0;
        end
      end
    end else begin
      bresp_d = RespDecerr;
    end
    if (!do_write) begin
      shell_we_o = 1'b0;
      map_we_o   = 1'b0;
      run_d    = 1'b0;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      aw_full_q     <= 1'b0;
      w_full_q      <= 1'b0;
      bvalid_q      <= 1'b0;
      bresp_q       <= RespOkay;
      run_q         <= 1'b0;
      shas_q        <= 2'b00;
      mhas_q        <= 1'b0;
      shell_words_q <= '0;
      map_words_q   <= '0;
    end else begin
      if (s_axil_awvalid_i && s_axil_awready_o) aw_full_q <= 1'b1;
      if (s_axil_wvalid_i && s_axil_wready_o) w_full_q <= 1'b1;
      if (do_write) begin
        aw_full_q <= 1'b0;
        w_full_q  <= 1'b0;
        bvalid_q  <= 1'b1;
        bresp_q   <= bresp_d;
        shas_q    <= shas_d;
        mhas_q    <= mhas_d;
        if (run_d) run_q <= 1'b1;
        if (shell_we_o && 64'(shell_waddr_o) >= shell_words_q) shell_words_q <= 64'(shell_waddr_o) + 64'd1;
        if (map_we_o && 64'(map_waddr_o) >= map_words_q) map_words_q <= 64'(map_waddr_o) + 64'd1;
      end else if (s_axil_bready_i) begin
        bvalid_q <= 1'b0;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (s_axil_awvalid_i && s_axil_awready_o) awaddr_q <= s_axil_awaddr_i;
    if (s_axil_wvalid_i && s_axil_wready_o) begin
      wdata_q <= s_axil_wdata_i;
      wstrb_q <= s_axil_wstrb_i;
    end
    if (do_write) begin
      sk_q  <= sk_d;
      sx_q  <= sx_d;
      sy_q  <= sy_d;
      mk_q  <= mk_d;
      mlo_q <= mlo_d;
    end
  end

  assign s_axil_bvalid_o = bvalid_q;
  assign s_axil_bresp_o  = bresp_q;

  logic unused;
  assign unused = ^{s_axil_awprot_i, s_axil_arprot_i, shell_off, map_off};

  assign run_o         = run_q;
  assign shell_words_o = shell_words_q;
  assign map_words_o   = map_words_q;

`ifndef SYNTHESIS
  // ---- Parameter sanity, at elaboration ----
  `VOXCD_ASSERT_INIT(AxilDataWidthKnown, AxilDw == 32 || AxilDw == 64)

  // ---- AXI4-Lite rules (AMBA AXI4): what this slave and the master driving it promise ----
  // A response, once valid, stays valid and unchanged until it is taken.
  `VOXCD_ASSERT(AxilBStable, s_axil_bvalid_o && !s_axil_bready_i |=> s_axil_bvalid_o && $stable(s_axil_bresp_o))
  `VOXCD_ASSERT(AxilRStable, s_axil_rvalid_o && !s_axil_rready_i |=>
                             s_axil_rvalid_o && $stable(s_axil_rdata_o) && $stable(s_axil_rresp_o))
  // AXI4-Lite has no EXOKAY.
  `VOXCD_ASSERT(AxilNoExokay, !(s_axil_bvalid_o && s_axil_bresp_o == 2'b01) &&
                              !(s_axil_rvalid_o && s_axil_rresp_o == 2'b01))
  // What the masters driving this top promise (their own checkers' rules; a failure here is theirs).
  `VOXCD_ASSERT(AxilAwStable, s_axil_awvalid_i && !s_axil_awready_o |=>
                              s_axil_awvalid_i && $stable(s_axil_awaddr_i))
  `VOXCD_ASSERT(AxilWStable, s_axil_wvalid_i && !s_axil_wready_o |=>
                             s_axil_wvalid_i && $stable(s_axil_wdata_i) && $stable(s_axil_wstrb_i))
  `VOXCD_ASSERT(AxilArStable, s_axil_arvalid_i && !s_axil_arready_o |=>
                              s_axil_arvalid_i && $stable(s_axil_araddr_i))
  // Inside: the device sees a write only while idle.
  `VOXCD_ASSERT(MemWriteIdle, !((shell_we_o || map_we_o) && (dev_busy_i || desc_full_i || checked_i)))
`endif

  // Functional coverage (docs/verification.md): each error response of the AXI4-Lite port.
  `VOXCD_COVER(CoverWriteRefused, s_axil_bvalid_o && s_axil_bresp_o == RespSlverr)
  `VOXCD_COVER(CoverWriteToNoRegister, s_axil_bvalid_o && s_axil_bresp_o == RespDecerr)
  `VOXCD_COVER(CoverReadRefused, s_axil_rvalid_o && s_axil_rresp_o == RespSlverr)
  `VOXCD_COVER(CoverReadOfNoRegister, s_axil_rvalid_o && s_axil_rresp_o == RespDecerr)

endmodule
