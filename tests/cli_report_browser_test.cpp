// The HTML report in a real browser (headless Chromium): a rendered report loads without console
// output or failed resources and every image decodes; and the checker itself catches a corrupted
// image, a missing file, console.error and an uncaught exception. Without Chromium these tests
// fail, naming the setup command that installs it.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "browser_check.h"
#include "cli/image_io.h"
#include "cli/report_html.h"
#include "cli_test_util.h"

namespace cli {
namespace {

using testing::BrowserCheck;
using testing::CheckInChromium;
using testing::ConsoleMessagesInLog;

Report BrowserReport() {
  std::vector<std::uint8_t> pixels(4 * 3 * 3);
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<std::uint8_t>(i * 7);
  Report report;
  report.title = "browser <check>";
  ReportSection section;
  section.title = "images";
  section.paragraphs = {"a & b"};
  section.images = {{"plain", EncodePng(4, 3, 3, pixels), 4, 3, 1}, {"zoomed", EncodePng(4, 3, 3, pixels), 4, 3, 8}};
  section.tables = {{"numbers", {"name", "value"}, {{"x", "1"}, {"y<z", "2"}}}};
  section.charts = {{"lanes", "lanes", {"stencil", "queue"}, {"active", "dead"}, {{10, 20}, {5, 0}}, true}};
  report.sections = {section};
  report.configurationJson = R"({"scene": "builtin:default"})";
  return report;
}

std::string Joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += "\n  " + line;
  return text;
}

std::string WithBeforeBodyEnd(std::string html, const std::string& markup) {
  const std::size_t end = html.rfind("</body>");
  EXPECT_NE(end, std::string::npos);
  if (end != std::string::npos) html.insert(end, markup);
  return html;
}

bool AnyContains(const std::vector<std::string>& lines, const std::string& text) {
  for (const std::string& line : lines) {
    if (line.find(text) != std::string::npos) return true;
  }
  return false;
}

class CliReportBrowser : public testing::ScratchDirTest {
 protected:
  // Writes `html` and loads it; the caller ASSERTs `ran` so a missing Chromium fails the test.
  BrowserCheck Check(const std::string& html) {
    const BrowserCheck check = CheckInChromium(testing::WriteFile(scratch_ / "report.html", html));
    std::printf("[ chromium ] %.2f s\n", check.seconds);
    return check;
  }
};

TEST(CliReportBrowserLog, FindsConsoleMessagesAmongChromiumNoise) {
  const std::string log =
      "/usr/bin/chromium: 9: [: 25276502016: unexpected operator\n"
      "[5770:5799:1124/102926.157712:ERROR:dbus/bus.cc:405] Failed to connect to the bus: x\n"
      "[5813:5813:1124/102926.181022:WARNING:media/gpu/vaapi/vaapi_wrapper.cc:1655] drmGetDevices2() x\n"
      "[5920:5920:1124/102927.119585:INFO:CONSOLE:1] \"boom\", source: file:///tmp/r.html (1)\n"
      "[5920:5920:1124/102927.119585:INFO:CONSOLE:3] \"two\n"
      "lines \"q\"\", source: file:///tmp/r.html (3)\n"
      "[0101/000000.000000:INFO:CONSOLE(7)] \"old format\", source: file:///tmp/r.html (7)\n"
      "[5920:5920:1124/102927.879949:WARNING:ui/base/idle/idle_linux.cc:111] None of the known D-Bus\n";
  const std::vector<std::string> messages = ConsoleMessagesInLog(log);
  ASSERT_EQ(messages.size(), 3u) << Joined(messages);
  EXPECT_EQ(messages[0], "\"boom\", source: file:///tmp/r.html (1)");
  EXPECT_EQ(messages[1], "\"two\nlines \"q\"\", source: file:///tmp/r.html (3)");
  EXPECT_EQ(messages[2], "\"old format\", source: file:///tmp/r.html (7)");
  EXPECT_TRUE(ConsoleMessagesInLog("[1:2:1124/102926.1:ERROR:dbus/bus.cc:405] CONSOLE x\n").empty());
}

TEST_F(CliReportBrowser, ReportLoadsCleanlyWithEveryImageDecoded) {
  const BrowserCheck check = Check(RenderHtml(BrowserReport()));
  ASSERT_TRUE(check.ran) << check.error;
  EXPECT_TRUE(check.consoleErrors.empty()) << Joined(check.consoleErrors);
  EXPECT_TRUE(check.loadErrors.empty()) << Joined(check.loadErrors);
  EXPECT_EQ(check.imagesTotal, 2) << check.rawLog;
  EXPECT_EQ(check.imagesLoaded, 2);
}

TEST_F(CliReportBrowser, CorruptedPngIsReportedAsNotDecoded) {
  Report report = BrowserReport();
  std::vector<std::uint8_t>& png = report.sections[0].images[1].png;
  ASSERT_GT(png.size(), 40u);
  for (std::size_t i = 16; i < png.size(); ++i) png[i] ^= 0x5A;  // past the signature and IHDR type
  const BrowserCheck check = Check(RenderHtml(report));
  ASSERT_TRUE(check.ran) << check.error;
  EXPECT_EQ(check.imagesTotal, 2) << check.rawLog;
  EXPECT_EQ(check.imagesLoaded, 1);
  ASSERT_EQ(check.loadErrors.size(), 1u) << Joined(check.loadErrors);
  EXPECT_EQ(check.loadErrors[0], "img zoomed");
}

TEST_F(CliReportBrowser, MissingFileIsReportedAsFailedLoad) {
  const BrowserCheck check =
      Check(WithBeforeBodyEnd(RenderHtml(BrowserReport()), "<img src='no-such-file.png' alt='missing'>"));
  ASSERT_TRUE(check.ran) << check.error;
  EXPECT_EQ(check.imagesTotal, 3) << check.rawLog;
  EXPECT_EQ(check.imagesLoaded, 2);
  EXPECT_EQ(check.loadErrors, std::vector<std::string>{"img missing"});
}

TEST_F(CliReportBrowser, ConsoleErrorIsReported) {
  const BrowserCheck check =
      Check(WithBeforeBodyEnd(RenderHtml(BrowserReport()), "<script>console.error('boom')</script>"));
  ASSERT_TRUE(check.ran) << check.error;
  ASSERT_EQ(check.consoleErrors.size(), 1u) << Joined(check.consoleErrors) << "\n" << check.rawLog;
  EXPECT_EQ(check.consoleErrors[0].rfind("\"boom\", source: file://", 0), 0u) << check.consoleErrors[0];
  EXPECT_EQ(check.imagesLoaded, 2);
}

TEST_F(CliReportBrowser, UncaughtExceptionIsReported) {
  const BrowserCheck check =
      Check(WithBeforeBodyEnd(RenderHtml(BrowserReport()), "<script>throw new Error('boom')</script>"));
  ASSERT_TRUE(check.ran) << check.error;
  EXPECT_TRUE(AnyContains(check.consoleErrors, "Uncaught Error: boom")) << Joined(check.consoleErrors) << "\n"
                                                                          << check.rawLog;
  EXPECT_EQ(check.imagesLoaded, 2);
}

TEST_F(CliReportBrowser, ErrorLoggedAfterLoadIsReported) {
  const BrowserCheck check = Check(WithBeforeBodyEnd(
      RenderHtml(BrowserReport()), "<script>setTimeout(function(){console.error('late')},1000)</script>"));
  ASSERT_TRUE(check.ran) << check.error;
  EXPECT_TRUE(AnyContains(check.consoleErrors, "\"late\"")) << Joined(check.consoleErrors) << "\n" << check.rawLog;
}

// Two groups of three images with different pixels, and the comparer.
Report ComparerReport() {
  Report report;
  report.title = "comparer";
  ReportSection images{"images", {}, {}, {}, {}};
  for (const std::string group : {"whole frame", "region 1"}) {
    for (const std::string label : {"truth", "aliased", "pass"}) {
      std::vector<std::uint8_t> pixels(4 * 4 * 3, static_cast<std::uint8_t>(40 * images.images.size()));
      images.images.push_back({label, EncodePng(4, 4, 3, pixels), 4, 4, group == "region 1" ? 8 : 1, group});
    }
  }
  ReportSection comparer{"compare", {}, {}, {}, {}};
  comparer.imageComparer = true;
  report.sections = {images, comparer};
  return report;
}

std::string Attribute(const BrowserCheck& check, const std::string& name) {
  std::string value;
  EXPECT_TRUE(testing::BodyAttribute(check.dom, name, value)) << name << " missing";
  return value;
}

// A script a reader's actions stand in for: after load it records what the viewer shows, uses the
// comparer's own controls, and records again.
constexpr const char* kDriveComparer = R"(<script>window.addEventListener('load',function(){
var view=document.getElementById('cmp-view'),imgs=view.getElementsByTagName('img'),b=document.body;
function visible(){return imgs[1].style.visibility==='visible'?imgs[1]:imgs[0];}
b.setAttribute('data-before',view.getAttribute('data-shown'));var src=visible().src;
b.setAttribute('data-region',document.getElementById('cmp-region').value);
b.setAttribute('data-zoom',document.getElementById('cmp-zoom').value+' '+imgs[0].width);
document.getElementById('cmp-flip').click();
b.setAttribute('data-after',view.getAttribute('data-shown'));
b.setAttribute('data-src-changed',String(visible().src!==src));
document.dispatchEvent(new KeyboardEvent('keydown',{key:'f'}));
b.setAttribute('data-key',view.getAttribute('data-shown'));
document.querySelector('input[name=cmp-mode][value=wipe]').click();
var wipe=document.getElementById('cmp-wipe');wipe.value='30';wipe.dispatchEvent(new Event('input'));
b.setAttribute('data-wipe',view.getAttribute('data-shown')+' / '+imgs[1].style.clipPath);});</script>)";

TEST_F(CliReportBrowser, ComparerFlipsAndWipesBetweenTwoImages) {
  const BrowserCheck check = Check(WithBeforeBodyEnd(RenderHtml(ComparerReport()), kDriveComparer));
  ASSERT_TRUE(check.ran) << check.error;
  EXPECT_TRUE(check.consoleErrors.empty()) << Joined(check.consoleErrors);
  EXPECT_EQ(check.imagesLoaded, check.imagesTotal) << Joined(check.loadErrors);
  EXPECT_EQ(check.imagesTotal, 8);  // six in the report, the viewer's two
  EXPECT_EQ(Attribute(check, "data-region"), "region 1");  // the first region, not the whole frame
  EXPECT_EQ(Attribute(check, "data-zoom"), "8 32");         // a 4-pixel crop fits 8x
  EXPECT_EQ(Attribute(check, "data-before"), "truth");
  EXPECT_EQ(Attribute(check, "data-after"), "aliased");
  EXPECT_EQ(Attribute(check, "data-src-changed"), "true");
  EXPECT_EQ(Attribute(check, "data-key"), "truth");
  EXPECT_EQ(Attribute(check, "data-wipe"), "truth | aliased / inset(0px 0px 0px 30%)");
}

TEST_F(CliReportBrowser, ComparerWithoutGroupedImagesSaysSo) {
  Report report = ComparerReport();
  report.sections.erase(report.sections.begin());
  const BrowserCheck check = Check(WithBeforeBodyEnd(
      RenderHtml(report),
      "<script>document.body.setAttribute('data-cmp',document.getElementById('cmp').textContent)</script>"));
  ASSERT_TRUE(check.ran) << check.error;
  EXPECT_TRUE(check.consoleErrors.empty()) << Joined(check.consoleErrors);
  EXPECT_EQ(Attribute(check, "data-cmp"), "No images to compare.");
}

}  // namespace
}  // namespace cli
