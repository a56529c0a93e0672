// The self-contained HTML report writer: base64 against RFC 4648's vectors, escaping, embedded
// images and inline charts, nothing fetched from a network, and refused chart data.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "cli/image_io.h"
#include "cli/report_html.h"

namespace cli {
namespace {

std::vector<std::uint8_t> TextBytes(const std::string& text) { return {text.begin(), text.end()}; }

TEST(CliReportHtml, Base64MatchesRfc4648Vectors) {
  EXPECT_EQ(Base64(TextBytes("")), "");
  EXPECT_EQ(Base64(TextBytes("f")), "Zg==");
  EXPECT_EQ(Base64(TextBytes("fo")), "Zm8=");
  EXPECT_EQ(Base64(TextBytes("foo")), "Zm9v");
  EXPECT_EQ(Base64(TextBytes("foob")), "Zm9vYg==");
  EXPECT_EQ(Base64(TextBytes("fooba")), "Zm9vYmE=");
  EXPECT_EQ(Base64(TextBytes("foobar")), "Zm9vYmFy");
}

TEST(CliReportHtml, EscapesMarkup) {
  EXPECT_EQ(EscapeHtml("<a href=\"x\">'&'</a>"), "&lt;a href=&quot;x&quot;&gt;&#39;&amp;&#39;&lt;/a&gt;");
}

Report SmallReport() {
  const std::vector<std::uint8_t> pixels(4 * 3 * 3, 128);
  Report report;
  report.title = "test <report>";
  ReportSection section;
  section.title = "images";
  section.paragraphs = {"a & b"};
  section.images = {{"grey", EncodePng(4, 3, 3, pixels), 4, 3, 1}, {"grey crop", EncodePng(4, 3, 3, pixels), 4, 3, 8}};
  section.tables = {{"numbers", {"name", "value"}, {{"x", "1"}, {"y<z", "2"}}}};
  section.charts = {{"lanes", "lanes", {"stencil", "queue"}, {"active", "dead"}, {{10, 20}, {5, 0}}, true}};
  report.sections = {section};
  report.configurationJson = R"({"scene": "builtin:default"})";
  return report;
}

TEST(CliReportHtml, EmbedsEverythingAndFetchesNothing) {
  const std::string html = RenderHtml(SmallReport());
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("<title>test &lt;report&gt;</title>"), std::string::npos);
  EXPECT_NE(html.find("src='data:image/png;base64,iVBORw0KGgo"), std::string::npos);  // the PNG signature
  EXPECT_NE(html.find("class='zoom' width='32' height='24'"), std::string::npos);
  EXPECT_NE(html.find("<svg"), std::string::npos);
  EXPECT_NE(html.find("y&lt;z"), std::string::npos);
  EXPECT_NE(html.find("&quot;scene&quot;"), std::string::npos);
  EXPECT_EQ(html.find("http:"), std::string::npos);
  EXPECT_EQ(html.find("https:"), std::string::npos);
  EXPECT_EQ(html.find("src='/"), std::string::npos);
  EXPECT_NE(html.find("data-images"), std::string::npos);
}

TEST(CliReportHtml, RefusesChartDataItCannotDraw) {
  Report report = SmallReport();
  report.sections[0].charts[0].values[1][0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(RenderHtml(report), std::invalid_argument);
  report = SmallReport();
  report.sections[0].charts[0].values[0].pop_back();
  EXPECT_THROW(RenderHtml(report), std::invalid_argument);
  report = SmallReport();
  report.sections[0].charts[0].values[0][0] = -1.0;
  EXPECT_THROW(RenderHtml(report), std::invalid_argument);
}

}  // namespace
}  // namespace cli
