#include "voxcd/host/sizing/detail/storage_report.h"

#include <string>

#include "voxcd/host/sizing/digits.h"

namespace voxcd::detail {

namespace {

using json = nlohmann::ordered_json;

std::string fmt(double v) { return digits_text(v, 4); }

// "sparse (BL 3)", or "dense".
std::string layout_name(const StorageLayout& l) {
  return l.config.sparse() ? "sparse (BL " + std::to_string(l.config.BL) + ")" : "dense";
}

// "shell 700 words in 2^10 x 72 bit, voxmap 40 table + 829 brick words in 2^10 x 64 bit x 1 copy (...)"
std::string words_text(const StorageLayout& l) {
  const DeviceConfig& c = l.config;
  const LayoutWords& w = l.words;
  std::string s = "shell " + std::to_string(w.shell) + " words in 2^" + std::to_string(c.SAW) + " x " +
                  std::to_string(3 * c.PW) + " bit, voxmap ";
  if (c.sparse())
    s += std::to_string(w.table) + " table + " + std::to_string(w.bricks) + " brick";
  else
    s += std::to_string(w.table);
  if (w.padding) s += " + " + std::to_string(w.padding) + " padding";
  const char* copies = c.banked() ? " (shared banks)" : c.voxmap_copies() > 1 ? " copies" : " copy";
  s += " words in 2^" + std::to_string(c.MAW) + " x " + std::to_string(c.MEMW) + " bit x " +
       std::to_string(c.voxmap_copies()) + copies;
  if (c.sparse()) s += " read at the table and the brick port";
  return s;
}

// "  dense         PW 8 ... TAGW 16: LANES 1, largest frame 7161 cycles; shell ...; 448 kbit (57344 bytes)"
void layout_line(std::ostream& o, const char* label, const StorageLayout& l) {
  o << label;
  if (!l.met()) {
    o << "cannot be met with the types stored " << storage_name(l.storage) << ": " << l.failed << "\n";
    return;
  }
  o << l.config.to_string() << ": LANES " << l.config.LANES << ", largest frame " << l.measure.max_cycles
    << " cycles; " << words_text(l) << "; " << bits_text(l.memory_bits()) << " (" << l.memory_bytes()
    << " bytes)\n";
}

// "rock: dense voxmap 160 words, shell 3434; sparse table 1 + bricks 128 words, shell 312"
void type_lines(std::ostream& o, const StorageChoice& s) {
  if (!s.dense.met() || !s.sparse.met()) return;
  for (size_t i = 0; i < s.dense.words.types.size(); ++i) {
    const TypeWords &d = s.dense.words.types[i], &p = s.sparse.words.types[i];
    o << "  type " << d.name << ": dense voxmap " << d.map() << " words, shell " << d.shell << "; sparse "
      << (p.map_sparse ? "table " + std::to_string(p.table) + " + bricks " + std::to_string(p.bricks)
                       : "voxmap " + std::to_string(p.table) + " (kept dense)");
    if (p.padding) o << " + padding " << p.padding;
    o << " words, shell " << p.shell << (p.shell_sparse ? "" : " (kept dense)") << "\n";
  }
}

// "voxmap copy 1024 x 64 bit x 1, 2 read ports (64 kbit): 2 RAMB36, 32 EBR"
std::string memory_text(const LayoutMemory& m) {
  const MemoryShape& s = m.shape;
  return m.what + " " + std::to_string(s.words) + " x " + std::to_string(s.width) + " bit x " +
         std::to_string(s.count) + (s.read_ports > 1 ? ", 2 read ports" : "") + " (" + bits_text(s.bits()) +
         "): " + fmt(m.ramb36) + " RAMB36, " + fmt(m.ebr) + " EBR";
}

std::string memories_text(const std::vector<LayoutMemory>& ms) {
  std::string s;
  for (const LayoutMemory& m : ms) s += (s.empty() ? "" : "; ") + memory_text(m);
  return s;
}

// The block RAM lines of one layout: as the RTL builds it, and with a table memory and a brick memory of their own.
void macro_lines(std::ostream& o, const std::string& name, const StorageLayout& l) {
  if (!l.met()) return;
  o << "  " << name << " built  " << memories_text(built_memories(l.config)) << "\n";
  const std::vector<LayoutMemory> split = split_memories(l.config, l.words);
  o << "  " << name << " split  " << memories_text({split.begin() + 1, split.end()})  // the shell banks as built
    << (l.words.bricks ? "" : "; no brick memory") << "\n";
}

}  // namespace

void storage_lines(std::ostream& o, const SizeReport& r) {
  const StorageChoice& s = r.storage;
  const StorageLayout& c = s.chosen();
  o << "storage         " << layout_name(c) << ", the types stored " << storage_name(c.storage) << " (voxcd simulate "
    << "--storage " << storage_name(c.storage) << "): " << s.why() << "\n";
  layout_line(o, "  dense         ", s.dense);
  layout_line(o, "  sparse        ", s.sparse);
  type_lines(o, s);
  o << "  block RAMs    " << kBlockRamSource << "; built: the memories as the RTL builds them, split: the table "
    << "port's words and the brick port's each in a memory of its own\n";
  macro_lines(o, "dense ", s.dense);
  macro_lines(o, "sparse", s.sparse);
}

namespace {

json memories_json(const std::vector<LayoutMemory>& ms) {
  json a = json::array();
  for (const LayoutMemory& m : ms)
    a.push_back({{"what", m.what}, {"words", m.shape.words}, {"width", m.shape.width}, {"count", m.shape.count},
                 {"read_ports", m.shape.read_ports}, {"bits", m.shape.bits()}, {"ramb36", m.ramb36},
                 {"ice40_ebr", m.ebr}});
  return a;
}

json types_json(const LayoutWords& w) {
  json a = json::array();
  for (const TypeWords& t : w.types)
    a.push_back({{"name", t.name}, {"map_sparse", t.map_sparse}, {"shell_sparse", t.shell_sparse},
                 {"table_words", t.table}, {"brick_words", t.bricks}, {"padding_words", t.padding},
                 {"shell_words", t.shell}});
  return a;
}

json layout_json(const StorageLayout& l) {
  json j = {{"types_stored", storage_name(l.storage)}, {"met", l.met()},
            {"failed", l.met() ? json(nullptr) : json(l.failed)}};
  if (!l.met()) return j;
  const LayoutWords& w = l.words;
  j.update({{"config_text", l.config.to_string()}, {"bl", l.config.BL}, {"lanes", l.config.LANES},
            {"max_cycles", l.measure.max_cycles}, {"mean_cycles", l.measure.mean_cycles},
            {"memory_bits", {{"shell", shell_memory_bits(l.config)}, {"voxmap", map_memory_bits(l.config)},
                             {"total", l.memory_bits()}}},
            {"memory_bytes", l.memory_bytes()},
            {"words", {{"shell", w.shell}, {"table", w.table}, {"bricks", w.bricks}, {"padding", w.padding}}},
            {"types", types_json(w)},
            {"memories_built", memories_json(built_memories(l.config))},
            {"memories_split", memories_json(split_memories(l.config, w))}});
  return j;
}

}  // namespace

json storage_json(const SizeReport& r) {
  const StorageChoice& s = r.storage;
  return {{"chosen", s.chose_sparse ? "sparse" : "dense"},
          {"bl", s.chosen().config.BL},
          {"types_stored", storage_name(s.chosen().storage)},
          {"fixed_by", s.fixed_by.empty() ? json(nullptr) : json(s.fixed_by)},
          {"why", s.why()},
          {"rule", "the storage fixed by --storage or the scene file's \"storage\" (dense or sparse); else the one "
                   "whose derived device has fewer bits of shell and voxmap memory, dense on a tie"},
          {"block_rams_estimate", kBlockRamSource},
          {"dense", layout_json(s.dense)},
          {"sparse", layout_json(s.sparse)}};
}

}  // namespace voxcd::detail
