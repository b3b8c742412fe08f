// Determinism across builds (the same bytes on every machine): a hash of every buffer
// of a set of small frames, pinned in golden/frame-hashes.txt. CI checks it in the Release build
// (AVX2 where the machine has it) and in the sanitizer build (built for any x86-64, SSE2), so
// both vector widths of the span and lighting loops must give the same bytes — and the same as
// when the hashes were written. After an intended change of the output, scripts/update-goldens.sh
// --write rewrites the file (SHADOWREF_UPDATE_GOLDENS=1) from the reference pipeline's frames; the
// fast executor at two threads must give the same hashes. A mismatch writes a failure report
// (support/golden_report.h) with both pipelines' frames.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"
#include "support/golden_report.h"

using namespace shadowref;

namespace {

const std::string kHashFile = std::string(SHADOWREF_SOURCE_DIR) + "/golden/frame-hashes.txt";

struct HashCase {
  std::string name, file;
  std::vector<std::string> overrides;
};

std::vector<HashCase> hashCases() {
  return {
      {"room-zfail", "scenes/room.yaml", {"shadow.method=zfail"}},
      {"room-zpass-unorm24", "scenes/room.yaml", {"shadow.method=zpass", "image.depth=unorm24"}},
      {"room-soft", "scenes/room.yaml", {"lights.0.soft.shape=square_y", "lights.0.soft.spacing=0.3"}},
      {"room-none", "scenes/room.yaml", {"shadow.method=none"}},
      {"pumpkins-auto", "scenes/pumpkins.yaml", {"shadow.method=auto"}},
      {"city16-zfail", "scenes/city16.yaml", {"shadow.method=zfail"}},
      {"outdoor-tsm", "scenes/outdoor.yaml", {"shadow.method=tsm", "shadow.map_size=256"}},
      {"spot-pcf", "scenes/spot.yaml", {"shadow.method=shadowmap", "shadow.pcf=3", "shadow.map_size=128"}},
      {"room-cube", "scenes/room.yaml", {"shadow.method=shadowmap", "shadow.map_size=128"}},
  };
}

// FNV-1a, 64 bits, over the bytes of every buffer in a fixed order.
class Fnv {
 public:
  template <class T>
  void add(const PixelVector<T>& v) {
    const auto* p = reinterpret_cast<const unsigned char*>(v.data());
    for (size_t i = 0; i < v.size() * sizeof(T); ++i) hash_ = (hash_ ^ p[i]) * 0x100000001b3ull;
    hash_ = (hash_ ^ v.size()) * 0x100000001b3ull;
  }
  uint64_t value() const { return hash_; }

 private:
  uint64_t hash_ = 0xcbf29ce484222325ull;
};

FrameResult renderHashCase(const HashCase& c, PipelineKind pipeline) {
  LoadOptions options;
  options.overrides = c.overrides;
  options.overrides.push_back("image.width=160");
  options.overrides.push_back("image.height=128");
  const Scene scene = loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/" + c.file, options);
  FrameOptions frame;
  frame.pipeline = pipeline;
  frame.threads = 2;
  return renderFrame(scene, frame);
}

std::string frameHash(const Framebuffer& fb) {
  Fnv h;
  h.add(fb.color());
  h.add(fb.depthCodes());
  h.add(fb.stencil());
  h.add(fb.accum());
  std::ostringstream s;
  s << std::hex << h.value();
  return s.str();
}

std::map<std::string, std::string> readHashes() {
  std::map<std::string, std::string> out;
  std::ifstream in(kHashFile);
  std::string name, hash;
  while (in >> name >> hash) out[name] = hash;
  return out;
}

}  // namespace

TEST_CASE("every buffer of the pinned frames hashes as in golden/frame-hashes.txt", "[golden][determinism]") {
  if (std::getenv("SHADOWREF_UPDATE_GOLDENS")) {
    std::ofstream out(kHashFile);
    for (const HashCase& c : hashCases())
      out << c.name << " " << frameHash(renderHashCase(c, PipelineKind::Reference).framebuffer) << "\n";
    SUCCEED("wrote " << kHashFile);
    return;
  }
  const std::map<std::string, std::string> pinned = readHashes();
  REQUIRE(pinned.size() == hashCases().size());
  for (const HashCase& c : hashCases()) {
    INFO(c.name);
    REQUIRE(pinned.count(c.name) == 1);
    const FrameResult reference = renderHashCase(c, PipelineKind::Reference);
    const FrameResult fast = renderHashCase(c, PipelineKind::Fast);
    const std::string referenceHash = frameHash(reference.framebuffer), fastHash = frameHash(fast.framebuffer);
    CHECK(referenceHash == pinned.at(c.name));
    CHECK(fastHash == pinned.at(c.name));
    if (referenceHash == pinned.at(c.name) && fastHash == pinned.at(c.name)) continue;
    // The file holds hashes, not pictures: the report shows the reference pipeline's frame (which
    // defines the goldens) beside the fast one. When the reference itself no longer hashes as
    // pinned, no picture of the pinned frame exists; the note says so.
    const std::string note =
        referenceHash == pinned.at(c.name)
            ? "The reference pipeline's frame hashes as pinned (" + referenceHash + "); the fast pipeline's hashes as " +
                  fastHash + "."
            : "The reference pipeline's frame no longer hashes as pinned (" + pinned.at(c.name) + " pinned, " +
                  referenceHash + " now): the output changed. Shown: the reference's frame now and the fast "
                  "pipeline's (" + fastHash + "). The accumulation buffer is hashed but not drawn.";
    const std::string page = testing::reportFrames(c.name, reference.framebuffer, fast.framebuffer, "fast pipeline", note);
    FAIL_CHECK(c.name << ": report " << page);
  }
}
