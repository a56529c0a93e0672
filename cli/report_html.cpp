// The self-contained HTML report (see report_html.h).

#include "cli/report_html.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace cli {

namespace {

// Eight colours distinguishable in print and by most colour-blind readers (Okabe-Ito).
constexpr const char* kSeriesColours[] = {"#0072B2", "#E69F00", "#009E73", "#D55E00",
                                          "#CC79A7", "#56B4E9", "#F0E442", "#000000"};

constexpr const char* kStyle = R"(body{font-family:system-ui,sans-serif;margin:2em;color:#222}p{max-width:75em}
h1{font-size:1.6em}h2{font-size:1.25em;border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:2em}
figure{display:inline-block;margin:.5em;vertical-align:top}figcaption{font-size:.85em;text-align:center}
img.zoom{image-rendering:pixelated}img:not(.zoom){max-width:46vw;height:auto}table{border-collapse:collapse;margin:.8em 0;font-size:.9em}
th,td{border:1px solid #ccc;padding:.25em .6em;text-align:right}th:first-child,td:first-child{text-align:left}
th{background:#f2f2f2}pre{background:#f7f7f7;padding:1em;overflow:auto;font-size:.8em}
svg text{font-family:system-ui,sans-serif;font-size:12px})";

// Placed first in <head>. Records elements whose resource failed to load (capture-phase 'error'
// events, which Chromium does not print to its console log), and on 'load' counts images that
// decoded; the headless-browser test reads body attributes data-images="ok/total" and data-errors
// (one failed element per line). Script errors and console output are left to the browser's log.
constexpr const char* kImageCheck = R"((function(){var failed=[];
window.addEventListener('error',function(e){var t=e.target;if(t&&t!==window&&t.tagName){
failed.push(t.tagName.toLowerCase()+' '+(t.getAttribute('alt')||String(t.src||t.href||'').slice(0,64)));}},true);
window.addEventListener('load',function(){
var imgs=document.images,ok=0;for(var i=0;i<imgs.length;i++){if(imgs[i].complete&&imgs[i].naturalWidth>0)ok++;}
document.body.setAttribute('data-images',ok+'/'+imgs.length);
document.body.setAttribute('data-errors',failed.join('\n'));});})();)";

// The image comparer (ReportSection::imageComparer): its controls, then a script that collects the
// report's grouped images (data-group, data-label) and shows two of one group stacked, the upper
// one hidden (flip) or clipped at the slider (wipe). The viewer's data-shown attribute names what
// is visible, for the headless-browser test.
constexpr const char* kComparerMarkup = R"(<div id='cmp'><p>
<label>A <select id='cmp-a'></select></label> <label>B <select id='cmp-b'></select></label>
<label>region <select id='cmp-region'></select></label>
<label>zoom <select id='cmp-zoom'><option value='1'>1x</option><option value='2'>2x</option><option value='4'>4x</option><option value='8'>8x</option></select></label>
<label><input type='radio' name='cmp-mode' value='flip' checked> flip</label>
<label><input type='radio' name='cmp-mode' value='wipe'> wipe</label>
<button id='cmp-flip' type='button'>flip A/B (key f)</button>
<input id='cmp-wipe' type='range' min='0' max='100' value='50' aria-label='wipe position'></p>
<p id='cmp-caption'></p><div id='cmp-view' style='position:relative;display:inline-block'></div></div>)";

constexpr const char* kComparerScript = R"((function(){
function $(id){return document.getElementById(id);}
var groups={},order=[],found=document.querySelectorAll('img[data-group]');
for(var i=0;i<found.length;i++){var g=found[i].getAttribute('data-group');
if(!groups[g]){groups[g]={};order.push(g);}groups[g][found[i].getAttribute('data-label')]=found[i];}
var view=$('cmp-view'),selA=$('cmp-a'),selB=$('cmp-b'),region=$('cmp-region'),zoom=$('cmp-zoom'),
wipe=$('cmp-wipe'),flip=$('cmp-flip'),showB=false;
if(order.length===0){$('cmp').textContent='No images to compare.';return;}
function layer(top){var img=document.createElement('img');img.className='zoom';
img.style.cssText='display:block'+(top?';position:absolute;left:0;top:0':'');view.appendChild(img);return img;}
var imgA=layer(false),imgB=layer(true);
function fill(sel,items,chosen){sel.textContent='';items.forEach(function(t){var o=document.createElement('option');
o.value=t;o.textContent=t;sel.appendChild(o);});sel.value=items.indexOf(chosen)>=0?chosen:items[0];}
function labels(){return Object.keys(groups[region.value]);}
function mode(){return document.querySelector('input[name=cmp-mode]:checked').value;}
function place(img,source,z){img.src=source.src;img.alt=source.getAttribute('data-label');
img.width=source.getAttribute('data-width')*z;img.height=source.getAttribute('data-height')*z;}
function update(){var g=groups[region.value],a=g[selA.value],b=g[selB.value],z=+zoom.value,w=mode()==='wipe';
place(imgA,a,z);place(imgB,b,z);wipe.disabled=!w;flip.disabled=w;
imgB.style.clipPath=w?'inset(0 0 0 '+wipe.value+'%)':'none';imgB.style.visibility=(w||showB)?'visible':'hidden';
var shown=w?selA.value+' | '+selB.value:(showB?selB.value:selA.value);view.setAttribute('data-shown',shown);
$('cmp-caption').textContent=w?'A left of the line: '+selA.value+'; B right of it: '+selB.value
:'Showing '+(showB?'B: ':'A: ')+shown;}
function regionChanged(){var a=selA.value,b=selB.value,l=labels();fill(selA,l,a);fill(selB,l,b);update();}
function toggle(){if(mode()!=='flip')return;showB=!showB;update();}
fill(region,order,order[Math.min(1,order.length-1)]);
var l=labels();fill(selA,l,l[0]);fill(selB,l,l[Math.min(1,l.length-1)]);
var width=+groups[region.value][l[0]].getAttribute('data-width'),z=8;while(z>1&&width*z>640)z/=2;zoom.value=String(z);
region.addEventListener('change',regionChanged);flip.addEventListener('click',toggle);
[selA,selB,zoom,wipe].forEach(function(e){e.addEventListener('input',update);});
document.querySelectorAll('input[name=cmp-mode]').forEach(function(e){e.addEventListener('change',update);});
document.addEventListener('keydown',function(e){if(e.key==='f'&&!/^(INPUT|SELECT|TEXTAREA)$/.test(e.target.tagName))toggle();});
update();})();)";

std::string Format(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

void CheckChart(const BarChart& chart) {
  if (chart.values.size() != chart.series.size()) {
    throw std::invalid_argument("chart '" + chart.title + "': " + std::to_string(chart.values.size()) +
                                " value rows for " + std::to_string(chart.series.size()) + " series");
  }
  for (const std::vector<double>& row : chart.values) {
    if (row.size() != chart.categories.size()) {
      throw std::invalid_argument("chart '" + chart.title + "': a series has " + std::to_string(row.size()) +
                                  " values for " + std::to_string(chart.categories.size()) + " categories");
    }
    for (const double v : row) {
      if (!std::isfinite(v) || v < 0.0) {
        throw std::invalid_argument("chart '" + chart.title + "': value " + Format(v) + " is not finite and >= 0");
      }
    }
  }
}

std::string RenderChart(const BarChart& chart) {
  CheckChart(chart);
  constexpr int kLabelWidth = 260, kPlotWidth = 560, kBarHeight = 14, kGap = 10, kLegend = 24;
  const std::size_t barsPerGroup = chart.stacked ? 1 : chart.series.size();
  const int groupHeight = static_cast<int>(barsPerGroup) * kBarHeight + kGap;
  double maximum = 0.0;
  for (std::size_t c = 0; c < chart.categories.size(); ++c) {
    double stack = 0.0;
    for (std::size_t s = 0; s < chart.series.size(); ++s) {
      stack += chart.values[s][c];
      maximum = std::max(maximum, chart.stacked ? stack : chart.values[s][c]);
    }
  }
  if (maximum <= 0.0) maximum = 1.0;
  const int height = kLegend + static_cast<int>(chart.categories.size()) * groupHeight + 20;
  std::ostringstream svg;
  svg << "<svg width='" << kLabelWidth + kPlotWidth + 90 << "' height='" << height
      << "' role='img' aria-label='" << EscapeHtml(chart.title) << "'>";
  for (std::size_t s = 0; s < chart.series.size(); ++s) {
    const int x = static_cast<int>(s) * 150;
    svg << "<rect x='" << x << "' y='4' width='12' height='12' fill='" << kSeriesColours[s % 8] << "'/>"
        << "<text x='" << x + 16 << "' y='14'>" << EscapeHtml(chart.series[s]) << "</text>";
  }
  for (std::size_t c = 0; c < chart.categories.size(); ++c) {
    const int top = kLegend + static_cast<int>(c) * groupHeight;
    svg << "<text x='0' y='" << top + kBarHeight - 2 << "'>" << EscapeHtml(chart.categories[c]) << "</text>";
    double offset = 0.0;
    for (std::size_t s = 0; s < chart.series.size(); ++s) {
      const double value = chart.values[s][c];
      const double x = kLabelWidth + (chart.stacked ? offset : 0.0) / maximum * kPlotWidth;
      const double width = value / maximum * kPlotWidth;
      const int y = top + (chart.stacked ? 0 : static_cast<int>(s) * kBarHeight);
      svg << "<rect x='" << Format(x) << "' y='" << y << "' width='" << Format(width) << "' height='"
          << kBarHeight - 2 << "' fill='" << kSeriesColours[s % 8] << "'><title>" << EscapeHtml(chart.series[s])
          << ": " << Format(value) << ' ' << EscapeHtml(chart.unit) << "</title></rect>";
      if (!chart.stacked) {
        svg << "<text x='" << Format(x + width + 4) << "' y='" << y + kBarHeight - 3 << "'>" << Format(value)
            << "</text>";
      }
      offset += value;
    }
  }
  svg << "<text x='" << kLabelWidth << "' y='" << height - 4 << "'>0</text><text x='" << kLabelWidth + kPlotWidth - 40
      << "' y='" << height - 4 << "'>" << Format(maximum) << ' ' << EscapeHtml(chart.unit) << "</text></svg>";
  return "<figure><figcaption>" + EscapeHtml(chart.title) + "</figcaption>" + svg.str() + "</figure>";
}

std::string RenderImage(const ReportImage& image) {
  const bool zoomed = image.displayScale > 1;
  std::ostringstream html;
  html << "<figure><img" << (zoomed ? " class='zoom'" : "");
  if (!image.group.empty()) {
    html << " data-group='" << EscapeHtml(image.group) << "' data-label='" << EscapeHtml(image.title)
         << "' data-width='" << image.width << "' data-height='" << image.height << "'";
  }
  html << " width='" << image.width * image.displayScale
       << "' height='" << image.height * image.displayScale << "' alt='" << EscapeHtml(image.title)
       << "' src='data:image/png;base64," << Base64(image.png) << "'><figcaption>" << EscapeHtml(image.title)
       << (zoomed ? " (x" + std::to_string(image.displayScale) + ")" : "") << "</figcaption></figure>";
  return html.str();
}

std::string RenderTable(const ReportTable& table) {
  std::ostringstream html;
  html << "<table><caption>" << EscapeHtml(table.title) << "</caption><tr>";
  for (const std::string& h : table.header) html << "<th>" << EscapeHtml(h) << "</th>";
  html << "</tr>";
  for (const std::vector<std::string>& row : table.rows) {
    html << "<tr>";
    for (const std::string& cell : row) html << "<td>" << EscapeHtml(cell) << "</td>";
    html << "</tr>";
  }
  html << "</table>";
  return html.str();
}

}  // namespace

std::string EscapeHtml(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

// RFC 4648 base64 with padding.
std::string Base64(const std::vector<std::uint8_t>& bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t b0 = bytes[i];
    const std::uint32_t b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0;
    const std::uint32_t b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
    const std::uint32_t triple = b0 << 16 | b1 << 8 | b2;
    out += kAlphabet[triple >> 18 & 63];
    out += kAlphabet[triple >> 12 & 63];
    out += i + 1 < bytes.size() ? kAlphabet[triple >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[triple & 63] : '=';
  }
  return out;
}

std::string RenderHtml(const Report& report) {
  std::ostringstream html;
  html << "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><script>" << kImageCheck
       << "</script><title>" << EscapeHtml(report.title)
       << "</title><style>" << kStyle << "</style></head><body><h1>" << EscapeHtml(report.title) << "</h1>";
  bool comparer = false;
  for (const ReportSection& section : report.sections) {
    html << "<section><h2>" << EscapeHtml(section.title) << "</h2>";
    for (const std::string& p : section.paragraphs) html << "<p>" << EscapeHtml(p) << "</p>";
    if (section.imageComparer && !comparer) html << kComparerMarkup;
    comparer = comparer || section.imageComparer;
    if (!section.images.empty()) {
      html << "<div>";
      for (const ReportImage& image : section.images) html << RenderImage(image);
      html << "</div>";
    }
    for (const BarChart& chart : section.charts) html << RenderChart(chart);
    for (const ReportTable& table : section.tables) html << RenderTable(table);
    html << "</section>";
  }
  html << "<section><h2>Configuration</h2><pre>" << EscapeHtml(report.configurationJson)
       << "</pre></section>";
  if (comparer) html << "<script>" << kComparerScript << "</script>";
  html << "</body></html>\n";
  return html.str();
}

}  // namespace cli
