#include "apps/map_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

#include "nav/mapmaker/parkways.hpp"
#include "pipeline/media/media.hpp"

namespace neopipe::apps {
namespace {

using Eigen::Vector2d;
namespace mm = nav::mapmaker;

struct Colour {
  int r, g, b;
};

struct Line {
  Vector2d a, b;
  Colour colour;
  double width;  // px
  bool dashed;
};
struct Disk {
  Vector2d centre;
  double radius;  // px
  Colour colour;
};
struct Box {
  Vector2d lo, hi;
  Colour colour;
  double width;
};
struct Label {
  Vector2d at;
  std::string text;
  Colour colour;
  double size;  // px
};

// Primitives in workspace mm; the backends map them to pixels (y up in the world, down on screen).
struct Drawing {
  Vector2d size;
  double scale = 1;    // px per mm
  double pad = 30;     // px
  double footer = 40;  // px below the workspace for the caption and legend lines
  std::vector<Box> boxes;
  std::vector<Line> lines;
  std::vector<Disk> disks;
  std::vector<Label> labels;

  Vector2d px(const Vector2d& p) const { return {pad + p.x() * scale, pad + (size.y() - p.y()) * scale}; }
  int width() const { return static_cast<int>(std::ceil(size.x() * scale + 2 * pad)); }
  int height() const { return static_cast<int>(std::ceil(size.y() * scale + 2 * pad + footer)); }
};

constexpr Colour kObject{20, 20, 20};
constexpr Colour kParkway{150, 150, 150};
constexpr Colour kTrajectory{120, 170, 230};
constexpr Colour kPath{220, 40, 40};
constexpr Colour kWindow{230, 140, 30};
constexpr Colour kBorder{90, 90, 90};

constexpr Colour kExecuted{150, 40, 180};
constexpr Colour kHeld{40, 160, 60};

Drawing draw(const mm::MapMaker& maker, const std::optional<mm::Route>& route, const ExecutedRoute* executed) {
  const mm::WorldViews& views = maker.views();
  Drawing d;
  d.size = maker.workspace().size;
  d.scale = std::clamp(900.0 / std::max(d.size.x(), d.size.y()), 0.02, 20.0);
  d.boxes.push_back({{0, 0}, d.size, kBorder, 1});
  for (const mm::Trajectory& t : maker.steps().trajectories()) {
    const Vector2d& a = views.position(t.from.object);
    d.lines.push_back({a, views.position(t.to), kTrajectory, 0.6, true});
  }
  for (const mm::ParkwayEdge& e : mm::isolated_parkway(views)) {
    d.lines.push_back({views.position(e.from), views.position(e.to), kParkway, 0.8, false});
  }
  const double r = std::max(2.0, 0.6 * maker.options().window.side * d.scale / 25);
  for (std::uint32_t i = 0; i < views.object_count(); ++i) d.disks.push_back({views.position(i), r, kObject});
  if (views.object_count() <= 400) {
    for (std::uint32_t i = 0; i < views.object_count(); ++i) {
      d.labels.push_back({views.position(i) + Vector2d(3 / d.scale, 3 / d.scale), std::to_string(i), kBorder, 9});
    }
  }
  std::string caption = fmt::format("{} objects, window {} mm", views.object_count(), maker.options().window.side);
  if (route) {
    const double a = maker.options().window.side;
    mm::Placement at{route->start, route->start_corner};
    const auto window = [&](const mm::Placement& p) {
      const Vector2d o = views.origin(p);
      d.boxes.push_back({o, o + Vector2d(a, a), kWindow, 1.2});
    };
    window(at);
    for (const mm::RouteStep& rs : route->steps) {
      d.lines.push_back({views.position(rs.step.from.object), views.position(rs.step.landmark), kPath, 2.4, false});
      if (&rs != &route->steps.back()) window({rs.step.landmark, rs.step.adjust});
    }
    d.disks.push_back({views.position(route->start), 2.2 * r, kPath});
    d.disks.push_back({views.position(route->goal), 2.2 * r, {40, 160, 60}});
    caption +=
        fmt::format("; route {} -> {} ({}): D {:.1f} mm, U {:.3f}, {} steps", route->start, route->goal,
                    mm::criterion_name(route->criterion), route->distance, route->unreliability, route->steps.size());
  }
  if (executed != nullptr) {
    const double a = maker.options().window.side;
    for (const Vector2d& o : executed->held_windows) d.boxes.push_back({o, o + Vector2d(a, a), kHeld, 1.0});
    for (std::size_t i = 1; i < executed->track.size(); ++i) {
      d.lines.push_back({executed->track[i - 1], executed->track[i], kExecuted, 1.4, false});
    }
    caption += "; " + executed->caption;
  }
  d.labels.push_back({{0, -22 / d.scale}, caption, kObject, 13});
  d.labels.push_back({{0, -42 / d.scale},
                      "grey: isolated parkway edges; blue dashed: trajectories; red: route from the red start to "
                      "the green goal; orange: the windows it holds",
                      kBorder,
                      11});
  if (executed != nullptr) {
    d.footer = 60;
    d.labels.push_back({{0, -60 / d.scale},
                        "purple: where the navigator's window centre really went; green: the windows where it held "
                        "a landmark",
                        kBorder,
                        11});
  }
  return d;
}

std::string hex(const Colour& c) {
  return fmt::format("#{:02x}{:02x}{:02x}", c.r, c.g, c.b);
}

std::string svg(const Drawing& d) {
  std::string out = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\">\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
      d.width(), d.height(), d.width(), d.height());
  for (const Box& b : d.boxes) {
    const Vector2d p = d.px({b.lo.x(), b.hi.y()});
    out += fmt::format(
        "<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"none\" stroke=\"{}\" "
        "stroke-width=\"{}\"/>\n",
        p.x(), p.y(), (b.hi.x() - b.lo.x()) * d.scale, (b.hi.y() - b.lo.y()) * d.scale, hex(b.colour), b.width);
  }
  for (const Line& l : d.lines) {
    const Vector2d a = d.px(l.a);
    const Vector2d b = d.px(l.b);
    out += fmt::format(
        "<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"{}\" stroke-width=\"{}\"{}/>\n", a.x(),
        a.y(), b.x(), b.y(), hex(l.colour), l.width, l.dashed ? " stroke-dasharray=\"4 3\"" : "");
  }
  for (const Disk& c : d.disks) {
    const Vector2d p = d.px(c.centre);
    out += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\" fill=\"{}\"/>\n", p.x(), p.y(), c.radius,
                       hex(c.colour));
  }
  for (const Label& t : d.labels) {
    const Vector2d p = d.px(t.at);
    out += fmt::format(
        "<text x=\"{:.2f}\" y=\"{:.2f}\" font-family=\"sans-serif\" font-size=\"{}\" fill=\"{}\">{}</text>\n", p.x(),
        p.y(), t.size, hex(t.colour), t.text);
  }
  return out + "</svg>\n";
}

cv::Mat png(const Drawing& d) {
  // Drawn at 2x and shrunk, for anti-aliased thin lines.
  constexpr int k = 2;
  cv::Mat image(d.height() * k, d.width() * k, CV_8UC3, cv::Scalar(255, 255, 255));
  const auto pt = [&](const Vector2d& p) {
    const Vector2d q = d.px(p) * k;
    return cv::Point(static_cast<int>(std::lround(q.x())), static_cast<int>(std::lround(q.y())));
  };
  const auto bgr = [](const Colour& c) { return cv::Scalar(c.b, c.g, c.r); };
  const auto thickness = [&](double w) { return std::max(1, static_cast<int>(std::lround(w * k))); };
  for (const Box& b : d.boxes) {
    cv::rectangle(image, pt({b.lo.x(), b.hi.y()}), pt({b.hi.x(), b.lo.y()}), bgr(b.colour), thickness(b.width),
                  cv::LINE_AA);
  }
  for (const Line& l : d.lines) {
    if (!l.dashed) {
      cv::line(image, pt(l.a), pt(l.b), bgr(l.colour), thickness(l.width), cv::LINE_AA);
      continue;
    }
    const double length = (l.b - l.a).norm() * d.scale;
    const int dashes = std::max(1, static_cast<int>(length / 7));
    for (int i = 0; i < dashes; ++i) {
      const Vector2d a = l.a + (l.b - l.a) * (static_cast<double>(i) / dashes);
      const Vector2d b = l.a + (l.b - l.a) * ((i + 0.57) / dashes);
      cv::line(image, pt(a), pt(b), bgr(l.colour), thickness(l.width), cv::LINE_AA);
    }
  }
  for (const Disk& c : d.disks) {
    cv::circle(image, pt(c.centre), static_cast<int>(std::lround(c.radius * k)), bgr(c.colour), cv::FILLED,
               cv::LINE_AA);
  }
  for (const Label& t : d.labels) {
    cv::putText(image, t.text, pt(t.at), cv::FONT_HERSHEY_SIMPLEX, t.size * k / 30.0, bgr(t.colour), 1, cv::LINE_AA);
  }
  cv::Mat small;
  cv::resize(image, small, cv::Size(d.width(), d.height()), 0, 0, cv::INTER_AREA);
  return small;
}

}  // namespace

void write_map_plot(const mm::MapMaker& maker, const std::optional<mm::Route>& route, const std::string& path,
                    const ExecutedRoute* executed) {
  const bool is_svg = path.ends_with(".svg");
  if (!is_svg && !path.ends_with(".png")) {
    throw std::runtime_error(fmt::format("--plot {}: the picture must be a .png or .svg file", path));
  }
  const Drawing d = draw(maker, route, executed);
  if (is_svg) {
    std::ofstream out(path);
    out << svg(d);
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write the plot", path));
    return;
  }
  if (!pipeline::media::write_image(path, png(d)))
    throw std::runtime_error(fmt::format("{}: cannot write the plot", path));
}

}  // namespace neopipe::apps
