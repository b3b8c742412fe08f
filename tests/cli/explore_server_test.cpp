// `shadowref explore` as a program: the server started on a free port, asked over HTTP as the page
// asks it. The pixels it serves for a state are the pixels `shadowref render` writes for the same
// -D values (read back with OpenImageIO); bad requests get 400 and never end the server; SIGTERM
// stops it with exit 0; --export writes a whole folder or nothing.
#include <catch2/catch.hpp>

#include <httplib.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include "support/cli_run.h"

extern char** environ;

namespace fs = std::filesystem;
using shadowref::testing::runShadowref;
using shadowref::testing::testScratch;

namespace {

// A running `shadowref explore ARGS --port 0`: its process and the port it printed.
class Server {
 public:
  explicit Server(const std::vector<std::string>& args) {
    std::vector<std::string> argv{SHADOWREF_CLI, "explore"};
    argv.insert(argv.end(), args.begin(), args.end());
    argv.push_back("--port");
    argv.push_back("0");
    std::vector<char*> raw;
    for (std::string& a : argv) raw.push_back(a.data());
    raw.push_back(nullptr);
    int out[2];
    REQUIRE(::pipe(out) == 0);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, out[1], 1);
    posix_spawn_file_actions_addclose(&actions, out[0]);
    posix_spawn_file_actions_addchdir_np(&actions, SHADOWREF_SOURCE_DIR);
    REQUIRE(posix_spawn(&pid_, raw[0], &actions, nullptr, raw.data(), environ) == 0);
    posix_spawn_file_actions_destroy(&actions);
    ::close(out[1]);
    std::string line;
    char c = 0;
    while (line.find('\n') == std::string::npos && ::read(out[0], &c, 1) == 1) line += c;
    ::close(out[0]);
    const size_t colon = line.rfind(':');
    REQUIRE(colon != std::string::npos);
    port_ = std::stoi(line.substr(colon + 1));
  }
  ~Server() {
    if (pid_ > 0) stop(SIGKILL);
  }
  int port() const { return port_; }
  // Sends the signal and returns the exit status (-1: it did not exit within 10 s, or died by a signal).
  int stop(int sig) {
    ::kill(pid_, sig);
    int status = 0;
    for (int i = 0; i < 1000; ++i) {
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    return -1;
  }

 private:
  pid_t pid_ = -1;
  int port_ = 0;
};

std::string query(const std::vector<std::string>& overrides, const std::string& extra = "") {
  std::string q;
  for (const std::string& o : overrides) {
    q += q.empty() ? "" : "&";
    q += "D=" + httplib::detail::encode_query_param(o);
  }
  if (!extra.empty()) q += (q.empty() ? "" : "&") + extra;
  return q;
}

// The RGB bytes of a PNG, top row first.
std::vector<uint8_t> pngRgb(const fs::path& file, int& width, int& height) {
  auto in = OIIO::ImageInput::open(file.string());
  REQUIRE(in);
  const OIIO::ImageSpec& spec = in->spec();
  width = spec.width;
  height = spec.height;
  std::vector<uint8_t> pixels(size_t(width) * size_t(height) * size_t(spec.nchannels));
  REQUIRE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data()));
  std::vector<uint8_t> rgb;
  for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
    for (int k = 0; k < 3; ++k) rgb.push_back(pixels[i * size_t(spec.nchannels) + size_t(k)]);
  return rgb;
}

// The served frame's RGB bytes (its RGBA without A).
std::vector<uint8_t> servedRgb(httplib::Client& client, const std::vector<std::string>& overrides, int& width,
                               int& height) {
  const httplib::Result r = client.Get("/api/frame?" + query(overrides, "view=frame"));
  REQUIRE(r);
  INFO(r->body.substr(0, 300));
  REQUIRE(r->status == 200);
  width = std::stoi(r->get_header_value("X-Width"));
  height = std::stoi(r->get_header_value("X-Height"));
  REQUIRE(r->body.size() == size_t(width) * size_t(height) * 4);
  std::vector<uint8_t> rgb;
  for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
    for (size_t k = 0; k < 3; ++k) rgb.push_back(uint8_t(r->body[i * 4 + k]));
  return rgb;
}

std::string renderArgs(const std::string& scene, const std::vector<std::string>& overrides, const fs::path& out) {
  std::string args = "render " + scene + " --quiet -o '" + out.string() + "'";
  for (const std::string& o : overrides) args += " -D '" + o + "'";
  return args;
}

}  // namespace

TEST_CASE("explore serves for a state the pixels render writes with the same -D values", "[cli][explore]") {
  const fs::path dir = testScratch() / "explore-same";
  fs::create_directories(dir);
  struct Case {
    std::string scene;
    std::vector<std::string> overrides;
  };
  // Each path of the server: the scene as written, camera and method changes (applied to the
  // loaded scene), a light moved by name (the same) and by number (a full load), shadow maps with
  // PCF, saturating one-sided stencil ops with a soft light on the built-in room.
  const std::vector<Case> cases{
      {"scenes/pumpkins.yaml", {}},
      {"scenes/pumpkins.yaml",
       {"camera.eye=[0.1098,1.3724,3.6614]", "camera.target=[0.4,0.35,1]", "shadow.method=zpass"}},
      {"scenes/pumpkins.yaml", {"lights.candle.position=[0.3,0.6,1.1]", "shadow.method=shadowmap", "shadow.pcf=3",
                                "shadow.map_size=512"}},
      {"scenes/pumpkins.yaml", {"lights.0.position=[0.3,0.6,1.1]", "shadow.method=shadowmap", "shadow.pcf=3",
                                "shadow.map_size=512"}},
      {"", {"shadow.two_sided=false", "shadow.wrap=false", "lights.ceiling.soft.shape=square_y", "image.width=200",
            "image.height=160"}},
  };
  std::map<std::string, std::unique_ptr<Server>> servers;
  for (const Case& c : cases) {
    CAPTURE(c.scene, c.overrides);
    auto& server = servers[c.scene];
    if (!server) server = std::make_unique<Server>(c.scene.empty() ? std::vector<std::string>{}
                                                                    : std::vector<std::string>{c.scene});
    httplib::Client client("127.0.0.1", server->port());
    client.set_read_timeout(120);
    int w = 0, h = 0, cw = 0, ch = 0;
    const std::vector<uint8_t> served = servedRgb(client, c.overrides, w, h);
    // The PNG the page asks for holds the same bytes (the page draws it without colour conversion).
    const httplib::Result asPng = client.Get("/api/frame?" + query(c.overrides, "view=frame&encoding=png"));
    REQUIRE(asPng);
    REQUIRE(asPng->status == 200);
    CHECK(asPng->get_header_value("Content-Type") == "image/png");
    std::ofstream(dir / "served.png", std::ios::binary) << asPng->body;
    int pw = 0, ph = 0;
    CHECK(pngRgb(dir / "served.png", pw, ph) == served);
    const fs::path png = dir / "cli.png";
    const shadowref::testing::CliRun run = runShadowref(renderArgs(c.scene, c.overrides, png));
    REQUIRE(run.status == 0);
    const std::vector<uint8_t> written = pngRgb(png, cw, ch);
    REQUIRE(cw == w);
    REQUIRE(ch == h);
    size_t differing = 0;
    for (size_t i = 0; i < served.size(); ++i) differing += served[i] != written[i];
    CHECK(differing == 0);
  }
  for (auto& [scene, server] : servers) CHECK(server->stop(SIGTERM) == 0);
}

TEST_CASE("explore renders with every core but one unless told, leaving one to the browser", "[cli][explore]") {
  // The cores this test (and so the server it starts) may run on.
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  REQUIRE(::sched_getaffinity(0, sizeof allowed, &allowed) == 0);
  const int cores = CPU_COUNT(&allowed);
  const std::vector<std::pair<std::vector<std::string>, int>> cases{
      {{}, std::max(1, cores - 1)}, {{"--threads", "0"}, cores}, {{"--threads", "3"}, 3}, {{"--threads", "1"}, 1}};
  for (const auto& [args, threads] : cases) {
    CAPTURE(args);
    std::vector<std::string> all{"-D", "image.width=40", "-D", "image.height=32"};
    all.insert(all.end(), args.begin(), args.end());
    Server server(all);
    httplib::Client client("127.0.0.1", server.port());
    client.set_read_timeout(120);
    const httplib::Result r = client.Get("/api/frame?view=frame&encoding=png");
    REQUIRE(r);
    REQUIRE(r->status == 200);
    CHECK(r->get_header_value("X-Threads") == std::to_string(threads));
    CHECK(server.stop(SIGTERM) == 0);
  }
}

TEST_CASE("explore's pixel history is render --pixel-history's, step for step", "[cli][explore]") {
  // Two lights: with z-fail each light's volume pass opens with a stencil clear; with a shadow map
  // each shaded fragment is followed by both lights' lookups. The server's JSON and the CLI's text
  // must list the same clears, fragments and lookups in the same order with the same values.
  const fs::path dir = testScratch() / "explore-history";
  fs::create_directories(dir);
  const std::vector<std::string> base{"image.width=64", "image.height=48"};
  Server server({"scenes/two_lights.yaml", "-D", base[0], "-D", base[1]});
  httplib::Client client("127.0.0.1", server.port());
  client.set_read_timeout(120);
  const std::regex clearLine(R"(^  clear(?:  stencil (\d+) -> (\d+))?)");
  const std::regex drawLine(R"(^  draw (\d+) .*  (front|back)  z=.*stencil test (pass|FAIL)  depth test (pass|FAIL|-)  stencil (\d+) -> (\d+))");
  const std::regex lookupLine(R"(^      lookup light (L\d+) .*?(?:texel \((\d+), (\d+)\).*)?result (\S+)$)");
  for (const std::string method : {"zfail", "shadowmap"}) {
    for (const char* pixel : {"32,20", "20,10", "50,30"}) {
      INFO(method << " pixel " << pixel);
      std::string px = pixel;
      const std::string x = px.substr(0, px.find(',')), y = px.substr(px.find(',') + 1);
      const auto cli = runShadowref(renderArgs("scenes/two_lights.yaml", {base[0], base[1], "shadow.method=" + method},
                                                 dir / "o.png") + " --pixel-history " + pixel);
      REQUIRE(cli.status == 0);
      std::vector<std::string> expected;
      std::istringstream lines(cli.out);
      for (std::string line; std::getline(lines, line);) {
        std::smatch m;
        if (std::regex_search(line, m, clearLine))
          expected.push_back("clear " + (m[1].matched ? m[1].str() + ">" + m[2].str() : std::string("-")));
        else if (std::regex_search(line, m, drawLine))
          expected.push_back("draw " + m[1].str() + " " + m[2].str() + " " + m[3].str() + " " + m[4].str() + " " +
                             m[5].str() + ">" + m[6].str());
        else if (std::regex_search(line, m, lookupLine))
          expected.push_back("lookup " + m[1].str() + " " + (m[2].matched ? m[2].str() + "," + m[3].str() : "-") + " " +
                             std::to_string(std::stod(m[4].str())));
      }
      const httplib::Result r = client.Get("/api/history?" + query({"shadow.method=" + method}, "x=" + x + "&y=" + y));
      REQUIRE(r);
      REQUIRE(r->status == 200);
      const nlohmann::json h = nlohmann::json::parse(r->body);
      std::vector<std::string> served;
      for (const nlohmann::json& s : h["steps"]) {
        if (s["type"] == "clear") {
          served.push_back("clear " + (s["stencil"].is_null() ? std::string("-")
                                                              : std::to_string(s["stencil"][0].get<int>()) + ">" +
                                                                    std::to_string(s["stencil"][1].get<int>())));
          continue;
        }
        const auto test = [](const nlohmann::json& v) { return v.is_null() ? std::string("-") : v.get<bool>() ? "pass" : "FAIL"; };
        served.push_back("draw " + std::to_string(s["draw"].get<int>()) + " " + s["facing"].get<std::string>() + " " +
                         test(s["stencilTest"]) + " " + test(s["depthTest"]) + " " +
                         std::to_string(s["stencilBefore"].get<int>()) + ">" + std::to_string(s["stencilAfter"].get<int>()));
        for (const nlohmann::json& l : s.value("lookups", nlohmann::json::array()))
          served.push_back("lookup " + l["light"].get<std::string>() + " " +
                           (l.contains("texel") ? std::to_string(l["texel"][0].get<int>()) + "," +
                                                      std::to_string(l["texel"][1].get<int>())
                                                : std::string("-")) +
                           " " + std::to_string(l["result"].get<double>()));
      }
      CHECK(served == expected);
      CHECK(h["fragments"].get<size_t>() == size_t(std::count_if(expected.begin(), expected.end(),
                                                               [](const std::string& e) { return e.starts_with("draw"); })));
      const auto has = [&](const std::string& prefix) {
        return std::any_of(served.begin(), served.end(), [&](const std::string& e) { return e.starts_with(prefix); });
      };
      if (method == "zfail")  // one stencil clear before each light's volumes
        CHECK(std::count_if(served.begin(), served.end(),
                            [](const std::string& e) { return e.starts_with("clear ") && e != "clear -"; }) == 2);
      if (method == "shadowmap") {
        CHECK(has("lookup L0"));
        CHECK(has("lookup L1"));
      }
    }
  }
  CHECK(server.stop(SIGTERM) == 0);
}

TEST_CASE("explore answers bad requests with 400 and a reason, and keeps serving", "[cli][explore]") {
  Server server({"scenes/two_lights.yaml", "-D", "image.width=64", "-D", "image.height=48"});
  httplib::Client client("127.0.0.1", server.port());
  client.set_read_timeout(60);
  const auto status = [&](const std::string& path) {
    const httplib::Result r = client.Get(path);
    REQUIRE(r);  // the server answered: it did not crash or hang up
    return std::make_pair(r->status, r->body);
  };
  // Each a 400 whose message names what is wrong.
  const std::vector<std::pair<std::string, std::string>> bad{
      {"/api/frame?view=nope", "view"},
      {"/api/frame?index=-1", "index"},
      {"/api/frame?index=1e3", "index"},
      {"/api/frame?signed=2", "signed"},
      {"/api/frame?view=frame&view=depth", "more than once"},
      {"/api/frame?bogus=1", "unknown parameter"},
      // Numbered after the explore command's own two -D.
      {"/api/frame?D=" + httplib::detail::encode_query_param("shadow.map_size=3"), "<command line>:3:"},
      {"/api/frame?D=" + httplib::detail::encode_query_param("camera.eye=[1,2"), "<command line>:3:"},
      {"/api/frame?D=" + httplib::detail::encode_query_param("image.width=5000") + "&D=" +
           httplib::detail::encode_query_param("image.height=5000"),
       "4096"},
      {"/api/frame?view=stencil&index=7", "light 7"},
      {"/api/frame?view=pass&index=99", "pass 99"},
      {"/api/frame?view=shadowmap", "no shadow map"},
      {"/api/history?x=64&y=0", "outside"},
      {"/api/history?x=3", "required"},
      {"/api/history?x=99999999999&y=0", "x:"},
  };
  for (const auto& [path, word] : bad) {
    CAPTURE(path);
    const auto [code, body] = status(path);
    CHECK(code == 400);
    CHECK(body.find(word) != std::string::npos);
  }
  std::string many = "/api/frame?";
  // Distinct values: the HTTP library keeps one of identical name=value pairs (harmless for -D,
  // where applying the same value twice changes nothing).
  for (int i = 0; i < 65; ++i) many += "D=" + httplib::detail::encode_query_param("camera.fov=" + std::to_string(30 + i)) + "&";
  CHECK(status(many).first == 400);

  // Random requests from pieces of good and bad ones: every answer is 200, 204 or 400, never 500
  // or a dropped connection.
  std::mt19937 random(47);
  const std::vector<std::string> names{"D", "view", "index", "signed", "x", "y", "seq", "", "d", "view[]"};
  const std::vector<std::string> values{
      "0", "1", "-1", "2147483648", "frame", "stencil", "pass", "depth", "visibility", "shadowmap", "volumes",
      "overlay", "", "%00", "%FF%FE", "camera.eye=[0,1,5]", "camera.eye=[nan,1,5]", "camera.fov=180",
      "shadow.method=zpass", "shadow.method=tsm", "shadow.method=x", "lights.key.position=[0,3,0]", "lights.9.range=1",
      "lights.key=off", "lights.fill=off", "shadow.map_size=8192", "shadow.pcf=15", "generator.houses=3",
      "image.width=1", "camera.near=0", "camera.eye=[1e308,0,0]", "ambient=[2,2,2]", "=", "==", "a.b.c.d.e=1"};
  const std::vector<std::string> paths{"/api/frame", "/api/history", "/api/stats", "/api/scene", "/api/save"};
  for (int i = 0; i < 120; ++i) {
    std::string q;
    const int params = int(random() % 4);
    for (int p = 0; p < params; ++p)
      q += (p ? "&" : "") + names[random() % names.size()] + "=" +
           httplib::detail::encode_query_param(values[random() % values.size()]);
    const std::string path = paths[random() % paths.size()] + "?" + q;
    CAPTURE(path);
    const auto [code, body] = status(path);
    CHECK((code == 200 || code == 204 || code == 400));
  }
  CHECK(status("/api/frame?view=frame").first == 200);
  CHECK(server.stop(SIGTERM) == 0);
}

TEST_CASE("explore --export writes the page and its views into a new folder, or nothing", "[cli][explore]") {
  const fs::path dir = testScratch() / "explore-export";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path out = dir / "handout";
  const std::string small = " -D image.width=160 -D image.height=128";
  const shadowref::testing::CliRun run = runShadowref("explore scenes/pumpkins.yaml --export '" + out.string() + "'" + small);
  INFO(run.err);
  REQUIRE(run.status == 0);
  for (const char* f : {"index.html", "explore.js", "explore.css", "data.js", "frame.png", "depth.png", "stencil-0.png",
                        "volumes.png", "overlay.png", "visibility-0.png", "pass-0.png"})
    CHECK(fs::exists(out / f));
  // The handout's frame is the frame render writes.
  CHECK(runShadowref("render scenes/pumpkins.yaml --quiet -o '" + (dir / "cli.png").string() + "'" + small).status == 0);
  int w = 0, h = 0, cw = 0, ch = 0;
  CHECK(pngRgb(out / "frame.png", w, h) == pngRgb(dir / "cli.png", cw, ch));
  const std::string html = shadowref::testing::slurp(out / "index.html");
  CHECK(html.find("<script src=\"data.js\"></script>") < html.find("<script src=\"explore.js\"></script>"));
  CHECK(shadowref::testing::slurp(out / "data.js").find("SHADOWREF_VALUES['stencil-0']") != std::string::npos);

  // A folder that holds something is not written into; a scene that does not load leaves nothing.
  const shadowref::testing::CliRun again = runShadowref("explore scenes/pumpkins.yaml --export '" + out.string() + "'");
  CHECK(again.status == 2);
  CHECK(again.err.find("not an empty folder") != std::string::npos);
  std::ofstream(dir / "broken.yaml") << "camera:\n  fov: 200\n";
  const shadowref::testing::CliRun broken =
      runShadowref("explore '" + (dir / "broken.yaml").string() + "' --export '" + (dir / "nothing").string() + "'");
  CHECK(broken.status == 2);
  CHECK(broken.err.find("broken.yaml:2:8:") != std::string::npos);
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.path().filename().string().starts_with("nothing");
  CHECK(entries == 0);
}

TEST_CASE("explore saves a state as a scene file that renders as the state does", "[cli][explore]") {
  const fs::path dir = testScratch() / "explore-save";
  fs::create_directories(dir);
  // A file with its own lights list and a generator with a generated light: moved, switched off,
  // the method and camera changed.
  for (const auto& [scene, overrides] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"scenes/two_lights.yaml",
            {"camera.eye=[1.5,4,7]", "lights.cool=off", "lights.warm.position=[-1,4,2]", "shadow.method=zfail"}},
           {"scenes/pumpkins.yaml",
            {"camera.eye=[0.1098,1.3724,3.6614]", "lights.candle.position=[0.45,0.3,1.0]", "shadow.method=zpass",
             "shadow.wrap=false"}}}) {
    CAPTURE(scene, overrides);
    Server server({scene, "-D", "image.width=160", "-D", "image.height=128"});
    httplib::Client client("127.0.0.1", server.port());
    client.set_read_timeout(60);
    const httplib::Result r = client.Get("/api/save?" + query(overrides));
    REQUIRE(r);
    REQUIRE(r->status == 200);
    // Neither scene reads a mesh file, so the saved file may live anywhere.
    const fs::path saved = dir / "saved.yaml";
    std::ofstream(saved) << r->body;
    std::vector<std::string> all{"image.width=160", "image.height=128"};
    all.insert(all.end(), overrides.begin(), overrides.end());
    const shadowref::testing::CliRun a = runShadowref(renderArgs(saved.string(), {}, dir / "saved.png"));
    INFO(r->body);
    INFO(a.err);
    REQUIRE(a.status == 0);
    REQUIRE(runShadowref(renderArgs(scene, all, dir / "state.png")).status == 0);
    int w = 0, h = 0;
    CHECK(pngRgb(dir / "saved.png", w, h) == pngRgb(dir / "state.png", w, h));
    CHECK(server.stop(SIGINT) == 0);
  }
}
