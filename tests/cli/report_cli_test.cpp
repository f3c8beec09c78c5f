// `tessim report` (docs/report.md) as a user meets it: a page from a real run, opened in headless
// Chromium (a declared dependency, scripts/setup.sh: a missing browser fails the test) —
// rendered, scripted without a console message, with no network request and every section in
// the DOM — and bad input: exit status 2, one error line, no file written. Also `tessim compare`
// with the timeline the statistics carry since schema 3.
#include <gtest/gtest.h>
#include <zlib.h>

#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include "app/report_html.hpp"
#include "model/mesh_io.hpp"
#include "sim/base/counter_registry.hpp"
#include "sim/config/config.hpp"
#include "sim/report/report.hpp"
#include "sim/run/simulate.hpp"
#include "tests/support/run_tessim.hpp"
#include "tests/support/temp_dir.hpp"

namespace tessim {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::run_tessim;
using testing::shell_quote;
using testing::TempDir;
using testing::TessimRun;

const char* const kMesh = "/usr/share/assimp/models/STL/sphereWithHole.stl";
const char* const kChromium = "/usr/bin/chromium";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The statistics and trace of a small run (sphereWithHole, L = 4, adaptive-free), in `dir`.
void simulate_into(const TempDir& dir, const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args{"sim", kMesh, "-L", "4", "--stats", (dir.path() / "stats.json").string()};
  args.insert(args.end(), extra.begin(), extra.end());
  const TessimRun r = run_tessim(args, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
}

struct BrowserRun {
  int status = -1;
  std::string out, err;
};

// Headless Chromium on a local page: no sandbox (containers), no GPU, its profile and HOME in
// `dir`, every host name unresolvable (nothing can leave the machine even if the page tried),
// console messages on stderr, and a NetLog of every request in `dir`/net.json.
BrowserRun chromium(const fs::path& page, const std::vector<std::string>& actions, const fs::path& dir) {
  const fs::path profile = dir / "chromium-profile", home = dir / "home";
  fs::create_directories(home);
  std::string cmd = "env HOME=" + shell_quote(home.string()) + " timeout -k 5 90 " + shell_quote(kChromium);
  for (const char* a :
       {"--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--disable-background-networking",
        "--disable-extensions", "--no-first-run", "--no-proxy-server", "--host-resolver-rules=MAP * ~NOTFOUND",
        "--enable-logging=stderr", "--v=0"}) {
    cmd += ' ';
    cmd += shell_quote(a);
  }
  cmd += ' ';
  cmd += shell_quote("--user-data-dir=" + profile.string());
  cmd += ' ';
  cmd += shell_quote("--log-net-log=" + (dir / "net.json").string());
  for (const std::string& a : actions) {
    cmd += ' ';
    cmd += shell_quote(a);
  }
  cmd += ' ';
  cmd += shell_quote("file://" + fs::absolute(page).string());
  const fs::path out = dir / "browser.out", err = dir / "browser.err";
  cmd += " >" + shell_quote(out.string()) + " 2>" + shell_quote(err.string());
  const int raw = std::system(cmd.c_str());
  BrowserRun r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

// Console messages (errors, uncaught exceptions, Content-Security-Policy violations) are logged
// as "...:CONSOLE..." lines; the page logs nothing of its own, so any is a failure.
std::vector<std::string> console_lines(const std::string& err) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < err.size()) {
    std::size_t end = err.find('\n', start);
    if (end == std::string::npos) end = err.size();
    const std::string line = err.substr(start, end - start);
    if (line.find("CONSOLE") != std::string::npos || line.find("Uncaught") != std::string::npos)
      lines.push_back(line);
    start = end + 1;
  }
  return lines;
}

// URLs the page asked the network stack for. Chromium's own background requests (component
// updates, time, sign-in) carry the initiator "not an origin"; a page opened from a file has the
// opaque origin "null", so anything else was requested by the page.
std::vector<std::string> page_requests(const fs::path& netlog) {
  const json j = json::parse(slurp(netlog));
  const int start_job = j["constants"]["logEventTypes"]["URL_REQUEST_START_JOB"].get<int>();
  std::vector<std::string> urls;
  for (const json& e : j["events"]) {
    // The job's start carries the URL and the initiator (its end, neither).
    if (e.value("type", -1) != start_job || !e.contains("params") || !e["params"].contains("url")) continue;
    const json& p = e["params"];
    if (p.value("initiator", std::string()) != "not an origin") urls.push_back(p["url"].get<std::string>());
  }
  return urls;
}

// Every src= and href= value: a data: image, an in-page anchor, or a relative path.
void expect_no_external_references(const std::string& html) {
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("url("), std::string::npos) << "CSS must not load anything";
  EXPECT_EQ(html.find("@import"), std::string::npos);
  for (const std::string attr : {"src=\"", "href=\""}) {
    for (std::size_t at = html.find(attr); at != std::string::npos; at = html.find(attr, at + 1)) {
      const std::size_t from = at + attr.size();
      const std::string value = html.substr(from, html.find('"', from) - from);
      const bool data = value.rfind("data:image/png;base64,", 0) == 0;
      const bool local = value.rfind("//", 0) != 0 && value.find(':') == std::string::npos;
      EXPECT_TRUE(data || local) << attr << value.substr(0, 80);
    }
  }
}

TEST(ReportCli, PageRendersInHeadlessChromiumWithoutNetworkOrConsoleErrors) {
  ASSERT_TRUE(fs::exists(kChromium)) << kChromium << " is missing: chromium is a dependency (scripts/setup.sh)";
  TempDir dir;
  const fs::path stats = dir.path() / "stats.json", trace = dir.path() / "trace.json", png = dir.path() / "pn.png";
  simulate_into(dir, {"--trace", trace.string(), "--trace-cycles", "2000"});
  TessimRun r = run_tessim({"render", kMesh, "-L", "3", "--size", "320x240", "-o", png.string()}, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  // The page in a directory of its own: links to the trace go up a level.
  fs::create_directories(dir.path() / "out");
  const fs::path page = dir.path() / "out" / "report.html";
  r = run_tessim({"report", stats.string(), "--image", png.string(), "--trace", trace.string(), "-o", page.string()},
                 dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("wrote " + page.string()), std::string::npos) << r.out;

  const std::string html = slurp(page);
  const json j = json::parse(slurp(stats));
  expect_no_external_references(html);
  EXPECT_NE(html.find("Content-Security-Policy"), std::string::npos);
  EXPECT_NE(html.find("href=\"../trace.json\""), std::string::npos) << "relative link to the trace";
  EXPECT_NE(html.find("<img src=\"data:image/png;base64,iVBORw0KGgo"), std::string::npos) << "the PNG, embedded";
  // Everything is in the file as written: the page needs no script. The script's mark is not.
  for (const char* id : {"summary", "bottleneck", "timeline", "classes", "analytic", "int", "configuration", "images",
                         "files", "timeline-chart", "analytic-chart", "footer"})
    EXPECT_NE(html.find(std::string("id=\"") + id + "\""), std::string::npos) << id;
  EXPECT_EQ(html.find("id=\"report-scripted\""), std::string::npos);

  // 1. The page as written: the DOM after its script ran, with no console message.
  const fs::path browse = dir.path() / "browse";
  fs::create_directories(browse);
  BrowserRun b = chromium(page, {"--dump-dom"}, browse);
  ASSERT_EQ(b.status, 0) << b.err;
  EXPECT_EQ(console_lines(b.err), std::vector<std::string>{});
  EXPECT_EQ(page_requests(browse / "net.json"), std::vector<std::string>{});
  const std::string& dom = b.out;
  EXPECT_NE(dom.find("id=\"report-scripted\""), std::string::npos) << "the inline script ran to its end";
  for (const char* id : {"summary", "bottleneck", "timeline", "classes", "analytic", "int", "configuration", "images",
                         "files"})
    EXPECT_NE(dom.find(std::string("<section id=\"") + id + "\""), std::string::npos) << id;
  EXPECT_NE(dom.find("<footer id=\"footer\""), std::string::npos);
  EXPECT_NE(dom.find("<svg id=\"timeline-chart\""), std::string::npos);
  EXPECT_NE(dom.find(j["bottleneck"].get<std::string>().substr(0, 20)), std::string::npos);
  EXPECT_NE(dom.find("schema_version " + std::to_string(j["schema_version"].get<int>())), std::string::npos);
  EXPECT_NE(dom.find(j["tool"]["version"].get<std::string>()), std::string::npos);
  const std::size_t buckets = j["timeline"]["buckets"].get<std::size_t>();
  std::size_t cells = 0;
  for (std::size_t at = dom.find("class=\"bucket\""); at != std::string::npos; at = dom.find("class=\"bucket\"", at + 1))
    ++cells;
  EXPECT_EQ(cells, buckets) << "one cell per timeline bucket";

  // 2. The same page with its script taken out (a browser with scripts off), as a screenshot.
  std::string no_script = html;
  const std::size_t s0 = no_script.find("<script>"), s1 = no_script.find("</script>");
  ASSERT_TRUE(s0 != std::string::npos && s1 != std::string::npos);
  no_script.erase(s0, s1 + 9 - s0);
  const fs::path plain = dir.write("out/plain.html", no_script);
  const fs::path shot_dir = dir.path() / "shot";
  fs::create_directories(shot_dir);
  const fs::path shot = shot_dir / "page.png";
  b = chromium(plain, {"--screenshot=" + shot.string(), "--window-size=1200,2000"}, shot_dir);
  ASSERT_EQ(b.status, 0) << b.err;
  EXPECT_EQ(console_lines(b.err), std::vector<std::string>{});
  EXPECT_EQ(page_requests(shot_dir / "net.json"), std::vector<std::string>{});
  ASSERT_TRUE(fs::exists(shot));
  auto in = OIIO::ImageInput::open(shot.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  const OIIO::ImageSpec spec = in->spec();
  EXPECT_EQ(spec.width, 1200);
  EXPECT_EQ(spec.height, 2000);
  ASSERT_GE(spec.nchannels, 3);
  std::vector<unsigned char> px(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, px.data()));
  // Not one colour: many distinct colours, the header's dark blue on top, and the TE classes'
  // colours (the timeline and the class bars).
  std::set<unsigned> colours;
  auto rgb_at = [&](std::size_t i) {
    const unsigned char* p = &px[i * static_cast<std::size_t>(spec.nchannels)];
    return static_cast<unsigned>(p[0]) << 16 | static_cast<unsigned>(p[1]) << 8 | p[2];
  };
  std::size_t busy_green = 0, int_orange = 0;
  for (std::size_t i = 0; i < px.size() / static_cast<std::size_t>(spec.nchannels); ++i) {
    const unsigned c = rgb_at(i);
    colours.insert(c);
    busy_green += c == 0x009E73;
    int_orange += c == 0xE69F00 || c == 0x56B4E9;  // int_limited, or starved_by_cpg on this CPG-bound run
  }
  EXPECT_GT(colours.size(), 100u);
  EXPECT_EQ(rgb_at(static_cast<std::size_t>(spec.width) * 20 + 600), 0x14324Fu) << "header background";
  EXPECT_GT(busy_green, 1000u);
  EXPECT_GT(int_orange, 1000u);
}

// Bad input: exit status 2, "tessim: error: FILE: ELEMENT: REASON", and no output file.
TEST(ReportCli, BadInputIsAnErrorAndWritesNothing) {
  TempDir dir;
  simulate_into(dir);
  const fs::path stats = dir.path() / "stats.json";
  const fs::path out = dir.path() / "report.html";
  json j = json::parse(slurp(stats));
  json no_version = j;
  no_version.erase("schema_version");
  json future = j;
  future["schema_version"] = 99;
  json no_cycles = j;
  no_cycles.erase("cycles");
  json bad_timeline = j;
  bad_timeline["timeline"]["int_busy"].erase(bad_timeline["timeline"]["int_busy"].size() - 1);
  const fs::path text_png = dir.write("text.png", "not a picture\n");
  std::string truncated = slurp(fs::path(TESSIM_SOURCE_DIR) / "docs/images/wuson_adaptive.png");
  truncated.resize(truncated.size() / 2);
  const fs::path half_png = dir.write("half.png", truncated);
  // A PNG with one byte of its image data flipped (its CRC no longer matches), and one whose
  // header claims 100 000 x 100 000 pixels (the header's CRC made right): both used to be embedded.
  std::string whole = slurp(fs::path(TESSIM_SOURCE_DIR) / "docs/images/wuson_adaptive.png");
  std::string flipped = whole;
  const std::size_t idat = flipped.find("IDAT");
  ASSERT_NE(idat, std::string::npos);
  flipped[idat + 20] = static_cast<char>(flipped[idat + 20] ^ 0x5a);
  const fs::path damaged_png = dir.write("damaged.png", flipped);
  std::string huge = whole;
  for (std::size_t at : {16u, 20u}) {  // IHDR width, height: 100 000 big-endian
    huge[at] = 0;
    huge[at + 1] = 1;
    huge[at + 2] = static_cast<char>(0x86);
    huge[at + 3] = static_cast<char>(0xa0);
  }
  const std::uint32_t crc = static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(huge.data() + 12), 17));  // type + 13 bytes of IHDR
  for (int i = 0; i < 4; ++i) huge[29 + i] = static_cast<char>(crc >> (24 - 8 * i));
  const fs::path huge_png = dir.write("huge.png", huge);

  struct Case {
    std::vector<std::string> args;
    std::string file, element;
  };
  const std::string s = stats.string(), o = out.string();
  const std::vector<Case> cases{
      {{"report", (dir.path() / "missing.json").string(), "-o", o}, (dir.path() / "missing.json").string(), "file"},
      {{"report", dir.path().string(), "-o", o}, dir.path().string(), "file"},
      {{"report", dir.write("empty.json", "").string(), "-o", o}, (dir.path() / "empty.json").string(), "JSON"},
      {{"report", dir.write("trunc.json", slurp(stats).substr(0, 500)).string(), "-o", o},
       (dir.path() / "trunc.json").string(), "JSON"},
      {{"report", dir.write("array.json", "[1, 2]").string(), "-o", o}, (dir.path() / "array.json").string(),
       "statistics"},
      {{"report", dir.write("nover.json", no_version.dump()).string(), "-o", o}, (dir.path() / "nover.json").string(),
       "schema_version"},
      {{"report", dir.write("future.json", future.dump()).string(), "-o", o}, (dir.path() / "future.json").string(),
       "schema_version"},
      {{"report", dir.write("nocycles.json", no_cycles.dump()).string(), "-o", o},
       (dir.path() / "nocycles.json").string(), "cycles"},
      {{"report", dir.write("badtl.json", bad_timeline.dump()).string(), "-o", o}, (dir.path() / "badtl.json").string(),
       "timeline.int_busy"},
      {{"report", s, "--image", (dir.path() / "none.png").string(), "-o", o}, (dir.path() / "none.png").string(),
       "--image"},
      {{"report", s, "--image", text_png.string(), "-o", o}, text_png.string(), "--image"},
      {{"report", s, "--image", half_png.string(), "-o", o}, half_png.string(), "--image"},
      {{"report", s, "--image", damaged_png.string(), "-o", o}, damaged_png.string(), "--image"},
      {{"report", s, "--image", huge_png.string(), "-o", o}, huge_png.string(), "--image"},
      {{"report", s, "--trace", (dir.path() / "none.json").string(), "-o", o}, (dir.path() / "none.json").string(),
       "--trace"},
      {{"report", s, "-o", (dir.path() / "no/such/dir/r.html").string()}, (dir.path() / "no/such/dir/r.html").string(),
       "-o"},
      {{"report", s, "-o", dir.path().string()}, dir.path().string(), "-o"},
      {{"report", s, "-o", s}, s, "-o"},
  };
  for (const Case& c : cases) {
    const TessimRun r = run_tessim(c.args, dir.path());
    const std::string want = "tessim: error: " + c.file + ": " + c.element + ": ";
    EXPECT_EQ(r.status, 2) << c.args[1] << "\n" << r.err;
    EXPECT_EQ(r.err.rfind(want, 0), 0u) << "want '" << want << "', got: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_FALSE(fs::exists(out)) << c.args[1];
    for (const std::string& e : dir.entries()) EXPECT_EQ(e.find(".tmp-"), std::string::npos) << e;
  }
  EXPECT_EQ(slurp(stats), j.dump(2) + "\n") << "-o onto the statistics left them alone";
  // An unwritable directory for -o (root ignores permissions, so only when they apply).
  const fs::path locked = dir.path() / "locked";
  fs::create_directories(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  if (std::ofstream(locked / "probe")) {
    fs::remove(locked / "probe");
  } else {
    const TessimRun r = run_tessim({"report", s, "-o", (locked / "r.html").string()}, dir.path());
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find((locked / "r.html").string() + ": -o: cannot open for writing"), std::string::npos) << r.err;
  }
  fs::permissions(locked, fs::perms::owner_all);
}

// Links are relative to the page's directory and percent-encoded; a waveform brings its gtkwave
// layout (written beside it by tessim cosim --wave) along.
TEST(ReportCli, LinksAreRelativeToThePage) {
  TempDir dir;
  simulate_into(dir);
  fs::create_directories(dir.path() / "waves");
  fs::create_directories(dir.path() / "pages");
  const fs::path wave = dir.write("waves/run 1.fst", "not really an FST file, only linked");
  dir.write("waves/run 1.gtkw", "[*] layout\n");
  const fs::path trace = dir.write("t.json", "{}");
  const fs::path page = dir.path() / "pages" / "r.html";
  const TessimRun r = run_tessim({"report", (dir.path() / "stats.json").string(), "--wave", wave.string(), "--trace",
                                  trace.string(), "-o", page.string()},
                                 dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = slurp(page);
  EXPECT_NE(html.find("href=\"../waves/run%201.fst\""), std::string::npos);
  EXPECT_NE(html.find("href=\"../waves/run%201.gtkw\""), std::string::npos);
  EXPECT_NE(html.find("href=\"../t.json\""), std::string::npos);
  EXPECT_NE(html.find("id=\"images\""), std::string::npos);
  EXPECT_NE(html.find("None given (<code>--image</code>)"), std::string::npos);
}

// Statistics of schema 2 (before the timeline) still make a page, saying what is missing.
TEST(ReportCli, SchemaTwoHasNoTimeline) {
  TempDir dir;
  simulate_into(dir);
  json j = json::parse(slurp(dir.path() / "stats.json"));
  j["schema_version"] = 2;
  j.erase("timeline");
  const fs::path old = dir.write("old.json", j.dump());
  const fs::path page = dir.path() / "old.html";
  const TessimRun r = run_tessim({"report", old.string(), "-o", page.string()}, dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = slurp(page);
  EXPECT_NE(html.find("id=\"timeline-missing\""), std::string::npos);
  EXPECT_EQ(html.find("id=\"timeline-chart\""), std::string::npos);
  EXPECT_NE(html.find("schema_version 2"), std::string::npos);
}

// `tessim compare` leaves the timeline out (its buckets are not figures of the run; two runs'
// buckets differ in width) and still compares everything else.
TEST(ReportCli, CompareLeavesTheTimelineOut) {
  TempDir a, b;
  simulate_into(a);
  simulate_into(b, {"--int-blocks", "3"});
  TessimRun r = run_tessim({"compare", (a.path() / "stats.json").string(), (b.path() / "stats.json").string()}, a.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find("timeline"), std::string::npos);
  EXPECT_NE(r.out.find("\ncycles "), std::string::npos);
  EXPECT_NE(r.out.find("config.int_blocks"), std::string::npos);
  r = run_tessim({"compare", (a.path() / "stats.json").string(), (b.path() / "stats.json").string(), "--csv"},
                 a.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find("timeline"), std::string::npos);
}

// The legend: every class of the counter registry (sim/base/counter_registry.hpp) of the TE,
// CPG and GPE with its colour (the run's own statistics: tests/sim/counter_registry_test.cpp).
TEST(ReportCli, LegendShowsEveryClassWithItsColour) {
  Mesh mesh = load_mesh("/usr/share/assimp/models/STL/sphereWithHole.stl");
  mesh.triangles.resize(6);
  sim::UnitConfig cfg;
  cfg.int_blocks = 3;
  cfg.tess_factor = 5;
  cfg.validate("test");
  app::ReportInput in;
  in.stats_name = "stats.json";
  const std::string page = app::report_html(sim::stats_json(sim::simulate(mesh, cfg)), in);
  int legend = 0;
  for (const sim::CounterRow& c : sim::kCounterRegistry) {
    if (c.block == sim::CounterBlock::Run || c.block == sim::CounterBlock::Int) continue;
    EXPECT_NE(page.find(std::string("background:") + c.colour + "\"></span>" + c.key + " "), std::string::npos)
        << c.name;
    ++legend;
  }
  EXPECT_EQ(legend, 7 + 4 + 4);  // TE, CPG and GPE classes
}

}  // namespace
}  // namespace tessim
