#include "saagen/report/plots.hpp"

#include "saagen/io/output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace saagen::report {
namespace {

struct Frame {
  double width = 760, height = 344;
  double left = 70, right = 430, top = 40, bottom = 270;  // the plot area's edges
  double x_min = 1, x_max = 2, y_min = -1, y_max = 1;
  double x(double cost) const { return left + (cost - x_min) / (x_max - x_min) * (right - left); }
  double y(double error) const { return bottom - (error - y_min) / (y_max - y_min) * (bottom - top); }
};

// "Nice" tick spacing (1, 2 or 5 x 10^k) for about `count` ticks over `span`.
double tick_step(double span, int count) {
  const double raw = span / count, magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (double factor : {1.0, 2.0, 5.0})
    if (raw <= factor * magnitude) return factor * magnitude;
  return 10.0 * magnitude;
}

// A tick's text: 0 as "0", others with their sign.
std::string signed_tick(double value, double step) {
  return std::abs(value) < step * 1e-6 ? std::string("0") : fmt::format("{:+.3g}", value);
}

Frame frame_for(const ContentTrade& trade) {
  Frame f;
  double x_max = 1.0, y_min = 0.0, y_max = 0.0;
  for (const TradePoint& p : trade.points) {
    x_max = std::max(x_max, p.cost);
    y_min = std::min(y_min, p.frontier ? p.against_none.image.low : p.against_none.image.mean);
    y_max = std::max(y_max, p.frontier ? p.against_none.image.high : p.against_none.image.mean);
  }
  const double x_pad = std::max((x_max - 1.0) * 0.06, 0.02), y_pad = std::max((y_max - y_min) * 0.08, 1e-4);
  f.x_min = 1.0 - x_pad, f.x_max = x_max + x_pad, f.y_min = y_min - y_pad, f.y_max = y_max + y_pad;
  return f;
}

std::string escape(std::string_view text) {
  std::string out;
  for (char c : text)
    out += c == '<' ? std::string("&lt;") : c == '>' ? std::string("&gt;") : c == '&' ? std::string("&amp;") : std::string(1, c);
  return out;
}

void axes(std::ostringstream& svg, const Frame& f, const ContentTrade& trade) {
  svg << fmt::format(R"s(<text x="{}" y="20" font-weight="bold">{}, {}: image error against cost (lower is better)</text>)s", f.left,
                     path_name(trade.path), content_name(trade.content))
      << "\n";
  svg << fmt::format(
             R"s(<line x1="{0}" y1="{1}" x2="{2}" y2="{1}" stroke="black"/><line x1="{0}" y1="{1}" x2="{0}" y2="{3}" stroke="black"/>)s",
             f.left, f.bottom, f.right, f.top)
      << "\n";
  const double x_step = tick_step(f.x_max - f.x_min, 4), y_step = tick_step(f.y_max - f.y_min, 4);
  for (double x = std::ceil(f.x_min / x_step) * x_step; x <= f.x_max; x += x_step)
    svg << fmt::format(R"s(<text x="{:.1f}" y="{}" text-anchor="middle">{:.3g}</text>)s", f.x(x), f.bottom + 16, x) << "\n";
  for (double y = std::ceil(f.y_min / y_step) * y_step; y <= f.y_max; y += y_step)
    svg << fmt::format(R"s(<text x="{}" y="{:.1f}" text-anchor="end">{}</text>)s", f.left - 5, f.y(y) + 4, signed_tick(y, y_step)) << "\n";
  svg << fmt::format(R"s(<text x="{}" y="{}" text-anchor="middle">shading cost: {}</text>)s", (f.left + f.right) / 2, f.bottom + 34,
                     escape(trade.cost_axis))
      << "\n";
  svg << fmt::format(R"s(<text x="14" y="{0}" transform="rotate(-90 14 {0})" text-anchor="middle">image error - no SAA's</text>)s",
                     (f.top + f.bottom) / 2)
      << "\n";
  // No SAA: the dashed line every point is compared with, and its point (1, 0).
  svg << fmt::format(R"s(<line x1="{0}" y1="{2:.1f}" x2="{1}" y2="{2:.1f}" stroke="#777" stroke-dasharray="4 3"/>)s", f.left, f.right,
                     f.y(0.0))
      << "\n";
  svg << fmt::format(R"s(<rect x="{:.1f}" y="{:.1f}" width="8" height="8" fill="black"/>)s", f.x(1.0) - 4, f.y(0.0) - 4) << "\n";
  svg << fmt::format(R"s(<text x="{:.1f}" y="{:.1f}">no SAA</text>)s", f.x(1.0) + 7, f.y(0.0) - 6) << "\n";
}

void background_points(std::ostringstream& svg, const Frame& f, const ContentTrade& trade) {
  for (const TradePoint& p : trade.points) {
    if (p.frontier) continue;
    const double x = f.x(p.cost), y = f.y(p.against_none.image.mean);
    if (p.engine)
      svg << fmt::format(R"s(<path d="M{:.1f} {:.1f}l4 4l-4 4l-4 -4z" fill="#e67e22"><title>{}</title></path>)s", x, y - 4,
                         escape(p.configuration))
          << "\n";
    else
      svg << fmt::format(R"s(<circle cx="{:.1f}" cy="{:.1f}" r="2.5" fill="#bbb"><title>{}</title></circle>)s", x, y,
                         escape(p.configuration))
          << "\n";
  }
}

// The frontier: its step line, each point with its interval, its label in the column at the
// right (pushed apart so no two overlap) and a leader line.
void frontier(std::ostringstream& svg, const Frame& f, const ContentTrade& trade) {
  std::vector<const TradePoint*> points;
  for (const TradePoint& p : trade.points)
    if (p.frontier) points.push_back(&p);
  const std::string colour = trade.path == Path::forward ? "#c0392b" : "#2471a3";
  std::string line = fmt::format("M{:.1f} {:.1f}", f.x(1.0), f.y(0.0));
  for (const TradePoint* p : points) line += fmt::format(" H{:.1f} V{:.1f}", f.x(p->cost), f.y(p->against_none.image.mean));
  svg << fmt::format(R"s(<path d="{}" fill="none" stroke="{}" stroke-opacity="0.4"/>)s", line, colour) << "\n";
  constexpr double kLineHeight = 14;
  std::vector<double> label_y;
  for (const TradePoint* p : points) label_y.push_back(f.y(p->against_none.image.mean) + 4);
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return label_y[a] < label_y[b]; });
  for (std::size_t k = 1; k < order.size(); ++k) label_y[order[k]] = std::max(label_y[order[k]], label_y[order[k - 1]] + kLineHeight);
  const double overflow = order.empty() ? 0.0 : label_y[order.back()] - (f.height - 8);
  if (overflow > 0)
    for (double& y : label_y) y -= overflow;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const TradePoint& p = *points[i];
    const double x = f.x(p.cost), y = f.y(p.against_none.image.mean);
    svg << fmt::format(R"s(<line x1="{0:.1f}" y1="{1:.1f}" x2="{0:.1f}" y2="{2:.1f}" stroke="{3}"/>)s", x, f.y(p.against_none.image.low),
                       f.y(p.against_none.image.high), colour)
        << "\n";
    svg << fmt::format(R"s(<circle cx="{:.1f}" cy="{:.1f}" r="4.5" fill="{}"/>)s", x, y, colour) << "\n";
    const bool chosen = p.configuration == trade.chosen;
    if (chosen) svg << fmt::format(R"s(<circle cx="{:.1f}" cy="{:.1f}" r="8" fill="none" stroke="black"/>)s", x, y) << "\n";
    svg << fmt::format(R"s(<line x1="{:.1f}" y1="{:.1f}" x2="{}" y2="{:.1f}" stroke="#ccc"/>)s", x + 5, y, f.right + 8, label_y[i] - 4)
        << "\n";
    svg << fmt::format(R"s(<text x="{}" y="{:.1f}"{}>{} ({}{})</text>)s", f.right + 12, label_y[i],
                       chosen ? R"s( font-weight="bold")s" : "", escape(p.configuration), decision::name(p.outcome),
                       chosen ? ", chosen" : "")
        << "\n";
  }
}

void legend(std::ostringstream& svg, const Frame& f, const ContentTrade& trade) {
  const double y = f.height - 12;
  svg << fmt::format(R"s(<circle cx="{}" cy="{}" r="2.5" fill="#bbb"/><text x="{}" y="{}">other configurations</text>)s", f.left + 4, y - 4,
                     f.left + 12, y)
      << "\n";
  svg << fmt::format(
             R"s(<path d="M{} {}l4 4l-4 4l-4 -4z" fill="#e67e22"/><text x="{}" y="{}">engine forms (at deferred-sum's cost)</text>)s",
             f.left + 160, y - 8, f.left + 168, y)
      << "\n";
  if (trade.chosen == "none")
    svg << fmt::format(R"s(<text x="{}" y="{}" font-weight="bold">chosen: no filter</text>)s", f.left + 410, y) << "\n";
}

}  // namespace

std::string trade_plot_name(Content content, Path path) { return fmt::format("trade_{}_{}.svg", content_name(content), path_name(path)); }
std::string trade_plot_name(const ContentTrade& trade) { return trade_plot_name(trade.content, trade.path); }

std::string trade_plot_svg(const ContentTrade& trade) {
  const Frame f = frame_for(trade);
  std::ostringstream svg;
  svg << "<!-- " << output_tag << " report -->\n";  // first: where saagen looks for its tag (output.cpp)
  svg << fmt::format(R"s(<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" font-family="sans-serif" font-size="11">)s",
                     f.width, f.height)
      << "\n";
  svg << fmt::format(R"s(<rect width="{}" height="{}" fill="white"/>)s", f.width, f.height) << "\n";
  axes(svg, f, trade);
  background_points(svg, f, trade);
  frontier(svg, f, trade);
  legend(svg, f, trade);
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace saagen::report
