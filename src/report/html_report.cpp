#include "slamkit/report/html_report.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace slamkit {

std::string HtmlReportTemplate();  // html_template.cpp: the page with @DATA@ for the data

namespace {

// Indices 0, s, 2s, ... and the last, at most about `limit` of `n`.
std::vector<std::size_t> Decimated(std::size_t n, std::size_t limit) {
  const std::size_t step = n > limit && limit > 0 ? (n + limit - 1) / limit : 1;
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < n; i += step) out.push_back(i);
  if (n > 0 && out.back() != n - 1) out.push_back(n - 1);
  return out;
}

// A JSON number that JSON can hold (infinity and NaN become null).
nlohmann::json Number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

nlohmann::json PathJson(const ReportPath& p, std::size_t limit) {
  nlohmann::json t = nlohmann::json::array(), x = t, y = t, th = t, c = t;
  const bool with_covariances = p.covariances.size() == p.poses.size();
  for (std::size_t i : Decimated(p.poses.size(), limit)) {
    t.push_back(p.poses[i].t_s);
    x.push_back(p.poses[i].pose.x());
    y.push_back(p.poses[i].pose.y());
    th.push_back(p.poses[i].pose.theta());
    if (with_covariances) {
      const Eigen::Matrix2d& m = p.covariances[i];
      c.push_back({Number(m(0, 0)), Number(m(0, 1)), Number(m(1, 1))});
    }
  }
  nlohmann::json out = {{"name", p.name}, {"color", p.color}, {"t", t}, {"x", x}, {"y", y},
                        {"th", th}};
  if (with_covariances) out["c"] = c;
  return out;
}

nlohmann::json SeriesJson(const ReportSeries& s, std::size_t limit) {
  nlohmann::json t = nlohmann::json::array(), v = t;
  for (std::size_t i : Decimated(std::min(s.t_s.size(), s.values.size()), limit)) {
    t.push_back(s.t_s[i]);
    v.push_back(Number(s.values[i]));
  }
  nlohmann::json out = {{"name", s.name}, {"t", t}, {"v", v}};
  if (s.band) out["band"] = {s.band->first, s.band->second};
  return out;
}

std::string Base64(const std::vector<std::uint8_t>& bytes) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t a = bytes[i];
    const std::uint32_t b = i + 1 < bytes.size() ? bytes[i + 1] : 0;
    const std::uint32_t c = i + 2 < bytes.size() ? bytes[i + 2] : 0;
    const std::uint32_t n = (a << 16) | (b << 8) | c;
    out += kDigits[(n >> 18) & 63];
    out += kDigits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

// The map shrunk by a whole factor until it fits `max_pixels`, each block its darkest pixel.
nlohmann::json MapJson(const OccupancyImage& image, std::size_t max_pixels) {
  int f = 1;
  while (static_cast<std::size_t>(image.width / f) * static_cast<std::size_t>(image.height / f) >
         max_pixels) {
    ++f;
  }
  const int w = image.width / f, h = image.height / f;
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      std::uint8_t darkest = 255;
      for (int dr = 0; dr < f; ++dr) {
        for (int dc = 0; dc < f; ++dc) {
          const std::size_t k = static_cast<std::size_t>(r * f + dr) * image.width + (c * f + dc);
          darkest = std::min(darkest, image.pixels[k]);
        }
      }
      pixels[static_cast<std::size_t>(r) * w + c] = darkest;
    }
  }
  // Rows are taken from the top (largest y): the rows a whole factor drops are at the bottom, so
  // the lower-left corner moves up by them (columns drop on the right: x stays).
  const double dropped_m = (image.height - h * f) * image.resolution_m;
  return {{"w", w},
          {"h", h},
          {"resolution", image.resolution_m * f},
          {"origin", {image.origin_m.x(), image.origin_m.y() + dropped_m}},
          {"pixels", Base64(pixels)}};
}

nlohmann::json LandmarksJson(const std::vector<ReportLandmark>& landmarks) {
  nlohmann::json out = nlohmann::json::array();
  for (const ReportLandmark& l : landmarks) {
    nlohmann::json j = {{"x", l.position_m.x()}, {"y", l.position_m.y()}, {"est", l.estimated}};
    if (l.covariance) {
      j["c"] = {(*l.covariance)(0, 0), (*l.covariance)(0, 1), (*l.covariance)(1, 1)};
    }
    out.push_back(j);
  }
  return out;
}

// Each snapshot as {t, l: [[x, y, cxx, cxy, cyy], ...]}, thinned to about `limit` landmarks.
nlohmann::json HistoryJson(const std::vector<ReportMapSnapshot>& history, std::size_t limit) {
  std::size_t total = 0;
  for (const ReportMapSnapshot& s : history) total += s.landmarks.size();
  const std::size_t keep = total > limit
                               ? std::max<std::size_t>(1, history.size() * limit / total)
                               : history.size();
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t i : Decimated(history.size(), keep)) {
    nlohmann::json l = nlohmann::json::array();
    for (const ReportLandmark& m : history[i].landmarks) {
      const Eigen::Matrix2d c = m.covariance.value_or(Eigen::Matrix2d::Zero());
      l.push_back({m.position_m.x(), m.position_m.y(), Number(c(0, 0)), Number(c(0, 1)),
                   Number(c(1, 1))});
    }
    out.push_back({{"t", history[i].t_s}, {"l", l}});
  }
  return out;
}

}  // namespace

std::string HtmlReport(const ReportData& data, const HtmlReportParams& params) {
  nlohmann::json payload = {{"title", data.title},
                            {"metrics", data.metrics},
                            {"paths", nlohmann::json::array()},
                            {"series", nlohmann::json::array()},
                            {"landmarks", LandmarksJson(data.landmarks)},
                            {"history", HistoryJson(data.map_history,
                                                    params.max_history_landmarks)}};
  for (const ReportPath& p : data.paths) {
    payload["paths"].push_back(PathJson(p, params.max_path_points));
  }
  for (const ReportSeries& s : data.series) {
    payload["series"].push_back(SeriesJson(s, params.max_series_points));
  }
  if (data.map) payload["map"] = MapJson(*data.map, params.max_map_pixels);
  // Inside <script>: "</" would end the element, so it is written as "<\/" (the same string).
  std::string json = payload.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  for (std::size_t at = json.find("</"); at != std::string::npos; at = json.find("</", at + 3)) {
    json.replace(at, 2, "<\\/");
  }
  std::string page = HtmlReportTemplate();
  page.replace(page.find("@DATA@"), 6, json);
  return page;
}

}  // namespace slamkit
