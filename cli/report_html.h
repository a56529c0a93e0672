#pragma once
// The self-contained HTML report: a document model (sections of side-by-side images, tables and
// bar charts) rendered to one HTML file with every image embedded as a data: URI and every chart
// as inline SVG, so it opens anywhere without a network. A small inline script records whether
// every image decoded (body attribute data-images="loaded/total") for the headless-browser test;
// another drives the image comparer (ReportSection::imageComparer).

#include <cstdint>
#include <string>
#include <vector>

namespace cli {

struct ReportImage {
  std::string title;
  std::vector<std::uint8_t> png;  // encoded PNG
  int width = 0, height = 0;      // of the PNG
  int displayScale = 1;           // > 1 shows a zoomed crop with nearest-neighbour pixels
  // Images of one group show the same pixels ("whole frame", "region 1"): the image comparer
  // offers every group and every image title in it.
  std::string group = {};
};

struct ReportTable {
  std::string title;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

// Grouped (or stacked) horizontal bars: one group per category, one bar per series.
struct BarChart {
  std::string title;
  std::string unit;
  std::vector<std::string> categories;
  std::vector<std::string> series;
  std::vector<std::vector<double>> values;  // [series][category], finite and >= 0
  bool stacked = false;
};

struct ReportSection {
  std::string title;
  std::vector<std::string> paragraphs;
  std::vector<ReportImage> images;
  std::vector<ReportTable> tables;
  std::vector<BarChart> charts;
  // Shows the image comparer: pick two images of a group, flip between them or wipe with a
  // slider, at 1x-8x nearest-neighbour zoom. It reuses the grouped images of the whole report.
  bool imageComparer = false;
};

struct Report {
  std::string title;
  std::vector<ReportSection> sections;
  std::string configurationJson;  // shown verbatim (escaped) at the end
};

// Throws std::invalid_argument naming the chart for a negative or non-finite value or a
// values/categories/series shape mismatch.
std::string RenderHtml(const Report& report);

std::string EscapeHtml(const std::string& text);
std::string Base64(const std::vector<std::uint8_t>& bytes);

}  // namespace cli
