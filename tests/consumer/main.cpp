// Renders through the installed library only (shadowref/shadowref.h) and prints what
// tests/consumer/run.sh compares with values the command line and README.md give:
//   stencil ROW: the z-pass and z-fail counts of row 173, x 676..687, of the pumpkin scene
//     (README: camera inside a volume, so z-pass is one short: -1 lit, 0 shadow; z-fail 0 and 1);
//   history: of pixel 400,220 of the room with z-fail, the last fragment that changed the stencil
//     and the last fragment (README: why the pixel is dark);
//   error: the message for a bad override.
#include <cstdio>
#include <string>

#include <shadowref/shadowref.h>

namespace api = shadowref::api;

int main() {
  try {
    const api::Scene pumpkins = api::Scene::fromFile("scenes/pumpkins.yaml");
    for (const char* method : {"zpass", "zfail"}) {
      api::RenderOptions options;
      options.method = method;
      options.threads = 2;
      const api::Frame frame = api::render(pumpkins, options);
      std::printf("stencil %s", method);
      for (int x = 676; x < 688; ++x) std::printf(" %d", int(int8_t(frame.stencil[frame.index(x, 173)])));
      std::printf("\n");
    }
    api::RenderOptions watch;
    watch.method = "zfail";
    watch.historyX = 400;
    watch.historyY = 220;
    const api::Frame room = api::render(api::Scene::fromFile("scenes/room.yaml"), watch);
    const api::FragmentRecord* changed = nullptr;
    for (const api::FragmentRecord& f : room.history)
      if (f.stencilBefore != f.stencilAfter) changed = &f;
    for (const api::FragmentRecord* f : {changed, room.history.empty() ? nullptr : &room.history.back()})
      if (f)
        std::printf("history draw %llu %s stencil %d -> %d\n", static_cast<unsigned long long>(f->draw), f->what.c_str(),
                    f->stencilBefore, f->stencilAfter);
    try {
      api::Scene::fromFile("scenes/minimal.yaml", {"image.width=banana"});
      std::printf("error none\n");
    } catch (const api::Error& e) {
      std::printf("error %s\n", e.what());
    }
    // The room's light circles: frame 12 at 8 fps is t = 1.5 s, its key [-2, 2.6, 0], so that
    // frame is the still room with the light written there; frame 0 is not.
    const api::Scene circle = api::Scene::fromFile("scenes/anim_room_circle.yaml", {"image.width=64", "image.height=48"});
    const api::Scene still = api::Scene::fromString(
        "generator: {type: room, size: [8, 3, 6], wall_thickness: 0.2}\n"
        "image: {width: 64, height: 48}\n"
        "lights:\n  - {name: ceiling, position: [-2, 2.6, 0]}\n"
        "shadow: {method: zfail}\n",
        "still.yaml");
    const api::Frame atKey = api::render(circle.at(12 / circle.fps()));
    std::printf("animation %d fps %g frame 12 same as still %d frame 0 differs %d\n", int(circle.animated()), circle.fps(),
                int(atKey.color == api::render(still).color), int(api::render(circle.at(0.0)).color != atKey.color));
    std::printf("version %s\n", api::version().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
  return 0;
}
