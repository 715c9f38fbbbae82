#include "voxcd/ref/config.h"

#include <algorithm>
#include <sstream>

namespace voxcd {

int DeviceConfig::acc_width() const {
  // A product M*p needs MW+PW bits; three of them MW+PW+2; adding t (TW bits) one more.
  return std::max(MW + PW + 2, TW) + 1;
}

namespace {
void require(bool ok, const std::string& what) {
  if (!ok) throw ConfigError("invalid device configuration: " + what);
}
}  // namespace

void DeviceConfig::validate() const {
  auto range = [](const char* name, int v, int lo, int hi) {
    require(v >= lo && v <= hi, std::string(name) + " = " + std::to_string(v) + " is outside " +
                                    std::to_string(lo) + ".." + std::to_string(hi));
  };
  range("PW", PW, 2, 32);
  range("PF", PF, 0, PW - 1);
  range("MW", MW, 2, 32);
  range("MF", MF, 0, MW - 1);
  range("TW", TW, 2, 64);
  require(TF() < TW, "TW = " + std::to_string(TW) + " leaves no integer bit above TF = MF + PF = " +
                         std::to_string(TF()));
  range("DW", DW, 1, 16);
  range("MEMW", MEMW, 2, 64);
  require((MEMW & (MEMW - 1)) == 0, "MEMW = " + std::to_string(MEMW) + " is not a power of two");
  range("LANES", LANES, 1, 64);
  range("SAW", SAW, 1, 24);
  range("MAW", MAW, 1, 28);
  range("TAGW", TAGW, 1, 32);
  require(SB == 2 || SB == 4 || SB == 8 || SB == 16, "SB = " + std::to_string(SB) + " is not 2, 4, 8 or 16");
  require(SB <= MEMW, "SB = " + std::to_string(SB) + " is wider than a voxmap word (MEMW = " +
                          std::to_string(MEMW) + ")");
  range("WB", WB, 1, std::min(TF(), 16));
  if (distance()) {
    require(MAW >= 3, "MAW = " + std::to_string(MAW) + " leaves no row for the 8 banks of a distance voxmap (SB = " +
                          std::to_string(SB) + " needs MAW >= 3)");
  }
  if (banked()) {
    range("BANKS", BANKS, 1, 64);
    require((BANKS & (BANKS - 1)) == 0, "BANKS = " + std::to_string(BANKS) + " is not a power of two");
    // A distance device splits each of its 8 parity banks BANKS ways.
    const int64_t banks = int64_t(BANKS) * (distance() ? 8 : 1);
    require(banks <= (int64_t{1} << std::min(MAW, 28)),
            (distance() ? "8 * BANKS = " + std::to_string(banks) + " banks (each parity bank split BANKS = " +
                              std::to_string(BANKS) + " ways) are"
                        : "BANKS = " + std::to_string(BANKS) + " is") +
                " more than the 2^MAW = " + std::to_string(1 << std::min(MAW, 28)) + " voxmap words");
  } else {
    require(BANKS == 0, "BANKS = " + std::to_string(BANKS) + " is negative (0: a voxmap copy per lane)");
  }
  range("DEPTH", depth, 0, kMaxDepth);
  require(BL == 0 || (BL >= 2 && BL <= 4), "BL = " + std::to_string(BL) + " is not 0 (dense only) or 2..4");
  if (sparse()) {
    // A shell brick word holds a 64-bit mask, a 6-bit step and the origin flag (docs/contract.md).
    require(3 * PW >= 72, "a sparse device's shell word (3 * PW = " + std::to_string(3 * PW) +
                              " bits) cannot hold a shell brick (72 bits: PW >= 24)");
    require(MEMW >= 8, "a sparse device's table word (MEMW = " + std::to_string(MEMW) +
                           ") cannot hold a rank and a code (MEMW >= 8)");
    if (distance())
      require(TF() >= WB + 3, "TF = " + std::to_string(TF()) + " leaves no room for the weights of a level-3 brick (" +
                                  "a sparse distance device needs TF >= WB + 3 = " + std::to_string(WB + 3) + ")");
  }
  require(TX == 0 || TX == 1, "TX = " + std::to_string(TX) + " is not 0 (lanes that multiply) or 1 (brick lanes)");
  require(TX == 0 || sparse(), "TX = 1 (brick lanes) needs a sparse device (BL > 0): its lanes transform the points "
                               "of shell bricks");
  // An index must be able to hold every in-grid value 0 .. 2^DW - 1 plus a sign.
  require(index_width() >= DW + 1, "the accumulator's integer part (" + std::to_string(index_width()) +
                                       " bits) cannot hold DW = " + std::to_string(DW));
}

std::string DeviceConfig::to_string() const {
  std::ostringstream s;
  s << "PW " << PW << " PF " << PF << " MW " << MW << " MF " << MF << " TW " << TW << " DW " << DW << " MEMW "
    << MEMW << " LANES " << LANES << " SAW " << SAW << " MAW " << MAW << " TAGW " << TAGW;
  if (distance()) s << " SB " << SB << " WB " << WB;
  if (banked()) s << " BANKS " << BANKS;
  if (depth != 0) s << " DEPTH " << depth;
  if (sparse()) s << " BL " << BL;
  if (brick_lanes()) s << " TX " << TX;
  return s.str();
}

bool DeviceConfig::same_widths(const DeviceConfig& o) const {
  return PW == o.PW && PF == o.PF && MW == o.MW && MF == o.MF && TW == o.TW && DW == o.DW && MEMW == o.MEMW &&
         SAW == o.SAW && MAW == o.MAW && TAGW == o.TAGW && SB == o.SB && (!distance() || WB == o.WB) &&
         BL == o.BL;
}

}  // namespace voxcd
