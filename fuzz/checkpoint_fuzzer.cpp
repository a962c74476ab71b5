/// @file checkpoint_fuzzer.cpp
/// @brief libFuzzer target: checkpoint files of `membrane run`, restarted.
/// Two tiny cases (a struck 2 x 2 square on Newmark, probes, reactions,
/// fields every 3 steps; the same as a large-deflection fabric on explicit
/// steps with a failure threshold that elements cross) are run once each to
/// a checkpoint at step 5; each input then edits one of them and restarts
/// the run from a fresh copy of its folder. Byte 0 chooses the case (bit 1)
/// and the edit (bit 0):
/// - 0: the rest is a list of 11-byte records (entry, operation and
///   index, 8 bytes of a double) that set values, resize or remove entries;
///   the file is rewritten by writeCheckpoint, so its checksum matches (what
///   a hostile editor does): the values meet the restart's own checks;
/// - 1: the rest XORs the bytes of the file from an offset (2 bytes) on:
///   the container itself (HDF5 structures, attributes, the checksum).
/// A lamina::Error (a refused checkpoint, or a divergence of an edited but
/// consistent state) is a pass; anything else, a crash or a hang, a finding.

#include "fuzz_input.hpp"
#include "membrane/io/case_file.hpp"
#include "membrane/io/checkpoint.hpp"
#include "membrane/run.hpp"

#include <cstring>
#include <iterator>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace lamina;

/// The Newmark case, or (@p fabric) the large-deflection one: explicit,
/// tension only, a failure strain the struck elements cross.
std::string caseText(bool fabric) {
  return std::string(fabric ? "model = \"large_deflection\"\n" : "") +
         "[mesh]\nLx = 1.0\nnx = 2\n[[section]]\nE = 1.0e9\nnu = 0.3\ndensity = 1000.0\n"
         "thickness = 1.0e-3\n" +
         (fabric ? "tension_only = true\nfailure_strain = 1.0e-7\n[time]\n"
                   "integrator = \"explicit\"\nt_end = 2.0e-3\n"
                 : "[time]\ndt = 1.0e-5\nt_end = 1.2e-4\n") +
         "[[fixed]]\nnodes = \"edges\"\n[[strike]]\nat = [0.5, 0.5]\nspeed = 1.0\n"
         "[[probe]]\nname = \"c\"\nat = [0.5, 0.5]\n[output]\nfield_every = 3\n";
}

/// The case, the folder of its run stopped at step 5, the checkpoint's content.
struct Base {
  Base(const std::string& text, const std::string& name) {
    const toml::table doc = core::parseTomlString(text, name + ".toml");
    model = membrane::buildModel(doc, name + ".toml",
                                 {"/nonexistent/lamina-fuzz-library.toml",
                                  std::string(LAMINA_SOURCE_DIR) + "/materials/catalog.toml"});
    dir = fuzz::scratchFile("marker", "").parent_path() / name;
    fs::remove_all(dir);
    membrane::RunOptions opt;
    opt.out_dir = dir;
    opt.quiet = true;
    opt.stop_at_step = 5;
    membrane::runModel(model, opt);
    checkpoint = membrane::readCheckpoint(membrane::checkpointPath(dir));
    std::ifstream in(membrane::checkpointPath(dir), std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  membrane::Model model;
  fs::path dir;
  membrane::Checkpoint checkpoint;
  std::string bytes;
};

/// Applies the 11-byte edit records of @p data to @p h.
void edit(membrane::History& h, const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> keys;
  for (const auto& [key, v] : h)
    keys.push_back(key);
  for (std::size_t at = 0; at + 11 <= size; at += 11) {
    const std::string& key = keys[data[at] % keys.size()];
    const int op = data[at + 1] >> 6, index = ((data[at + 1] & 0x3f) << 8) | data[at + 2];
    double x = 0;
    std::memcpy(&x, data + at + 3, sizeof x);
    Eigen::VectorXd& v = h[key];
    if (op == 0 && v.size() > 0)
      v[index % v.size()] = x;
    else if (op == 1)
      v.conservativeResize(index % 64);
    else if (op == 2)
      h.erase(key);
    else if (v.size() > 0) // a plausible value: a small integer, or a value scaled
      v[index % v.size()] = data[at + 3] & 1 ? double(data[at + 4]) - 8 : v[index % v.size()] * 2;
  }
}

} // namespace

/// HDF5 1.10 sizes some metadata buffers by lengths read from the file and
/// treats a failed malloc as an error (our lamina::Error): outside ASan a
/// corrupted length of exabytes returns NULL and the checkpoint is refused.
/// ASan aborts on such a request instead, unless told to return NULL as the
/// C library does. (Requests below 1 TB still meet libFuzzer's
/// -rss_limit_mb: a corrupted size that really allocates is a finding.)
extern "C" const char* __asan_default_options() {
  return "allocator_may_return_null=1";
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const Base newmark(caseText(false), "newmark"), fabric(caseText(true), "fabric");
  if (size < 1)
    return 0;
  const Base& base = data[0] & 2 ? fabric : newmark;
  const fs::path run = base.dir.parent_path() / "run";
  fs::remove_all(run);
  fs::copy(base.dir, run, fs::copy_options::recursive);
  const fs::path file = membrane::checkpointPath(run);
  if ((data[0] & 1) == 0) {
    membrane::Checkpoint c = base.checkpoint;
    edit(c.data, data + 1, size - 1);
    membrane::writeCheckpoint(file, c);
  } else if (size >= 3) {
    std::string bytes = base.bytes;
    const std::size_t from = ((std::size_t(data[1]) << 8) | data[2]) % bytes.size();
    for (std::size_t i = 3; i < size && from + i - 3 < bytes.size(); ++i)
      bytes[from + i - 3] = static_cast<char>(bytes[from + i - 3] ^ data[i]);
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  }
  membrane::RunOptions opt;
  opt.out_dir = run;
  opt.quiet = true;
  opt.restart = true;
  return fuzz::guarded([&] { membrane::runModel(base.model, opt); });
}
