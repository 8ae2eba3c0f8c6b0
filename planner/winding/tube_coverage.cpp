#include "planner/winding/tube_coverage.h"

#include <algorithm>
#include <cmath>

namespace windplan {

namespace {

// A station's figures from its bins' band stacks (per family), and the report's running worst.
// bin: each bin's length along the loop (nullptr: n equal bins, counted as whole numbers).
void close_station(const std::array<std::vector<int>, 2>& stack, const std::vector<double>* bin,
                   double loop, double band_length, const std::array<double, 2>& fam_length,
                   StationCoverage* st, CoverageReport* rep, double* plies) {
  const int n = static_cast<int>(stack[0].size());
  const double total = bin ? loop : n;
  for (int fam = 0; fam < 2; ++fam) {
    double bare = 0.0, run = 0.0, widest = 0.0, first_run = -1.0;
    for (int i = 0; i < n; ++i) {
      st->max_stack = std::max(st->max_stack, stack[fam][i]);
      if (stack[fam][i] == 0) {
        const double len = bin ? (*bin)[i] : 1.0;
        bare += len;
        run += len;
      } else {
        if (first_run < 0.0) first_run = run;
        widest = std::max(widest, run);
        run = 0.0;
      }
    }
    // The gap that wraps round the seam joins the last run to the first.
    widest = std::max(widest, first_run < 0.0 ? total : run + first_run);
    st->family_bare[fam] = bare / total;
    st->widest_gap = std::max(st->widest_gap, bin ? widest : loop * widest / n);
  }
  st->bare_fraction = std::max(st->family_bare[0], st->family_bare[1]);
  st->mean_plies = band_length / loop;
  st->cover_factor = std::min(fam_length[0], fam_length[1]) / loop;
  rep->bare_fraction = std::max(rep->bare_fraction, st->bare_fraction);
  rep->widest_gap = std::max(rep->widest_gap, st->widest_gap);
  rep->max_stack = std::max(rep->max_stack, st->max_stack);
  rep->cover_factor = std::min(rep->cover_factor, st->cover_factor);
  *plies += st->mean_plies;
  rep->stations.push_back(*st);
}

}  // namespace

CoverageReport measure_tube_coverage(const TubeCentreLine& line,
                                     const std::vector<Circuit>& circuits, double band_width,
                                     double s0, double s1, int stations) {
  CoverageReport rep;
  std::vector<double> s;
  std::vector<const FibrePoint*> pts;
  for (const Circuit& c : circuits) {
    for (const FibrePoint& q : c.points) {
      double si = 0.0, th = 0.0, d = 0.0;
      line.locate(q.position, &si, &th, &d);
      s.push_back(si);
      pts.push_back(&q);
    }
    s.push_back(std::nan(""));  // no segment between circuits' lists (they share a point)
    pts.push_back(nullptr);
  }
  const double r = line.tube_radius(), loop = 2.0 * M_PI * r;
  const int n = 3600;
  double plies = 0.0;
  rep.cover_factor = 1e300;
  for (int k = 0; k < std::max(2, stations); ++k) {
    const double sc = s0 + (s1 - s0) * k / (std::max(2, stations) - 1);
    const TubeFrame f = line.frame(sc);
    StationCoverage st;
    st.station = sc;
    st.loop_length = loop;
    std::array<std::vector<int>, 2> stack{std::vector<int>(n, 0), std::vector<int>(n, 0)};
    double band_length = 0.0;
    std::array<double, 2> fam_length = {0.0, 0.0};
    for (std::size_t j = 0; j + 1 < s.size(); ++j) {
      // Half-open, so that a point exactly on the station counts once.
      if (!pts[j] || !pts[j + 1] || (s[j] < sc) == (s[j + 1] < sc)) continue;
      const double w = (sc - s[j]) / (s[j + 1] - s[j]);
      const Vec3 p = (1 - w) * pts[j]->position + w * pts[j + 1]->position - f.c;
      const double th = std::atan2(p.dot(f.v), p.dot(f.u));
      const double ca = std::max(1e-6, std::abs(pts[j]->tangent.dot(f.t)));
      // A segment along the section circle (a dwell on pins lying on the station) would lay a
      // trace of any length: one turn at most.
      const double width = std::min(2.0 * M_PI, band_width / (r * ca));  // rad
      const int fam = s[j + 1] > s[j] ? 0 : 1;
      ++st.bands[fam];
      fam_length[fam] += width * r;
      band_length += width * r;
      const int a = static_cast<int>(std::floor((th - 0.5 * width) / (2 * M_PI) * n));
      const int m = static_cast<int>(std::lround(width / (2 * M_PI) * n));
      for (int i = 0; i < m; ++i) ++stack[fam][((a + i) % n + n) % n];
    }
    close_station(stack, nullptr, loop, band_length, fam_length, &st, &rep, &plies);
  }
  rep.mean_plies = plies / rep.stations.size();
  return rep;
}

CoverageReport measure_tube_coverage(const TubeSurface& surface,
                                     const std::vector<Circuit>& circuits, double band_width,
                                     double s0, double s1, int stations) {
  CoverageReport rep;
  std::vector<double> s, th;
  std::vector<const FibrePoint*> pts;
  for (const Circuit& c : circuits) {
    for (const FibrePoint& q : c.points) {
      double si = 0.0, ti = 0.0, d = 0.0;
      surface.locate(q.position, &si, &ti, &d);
      s.push_back(si);
      th.push_back(ti);
      pts.push_back(&q);
    }
    s.push_back(std::nan(""));
    th.push_back(0.0);
    pts.push_back(nullptr);
  }
  const int n = 3600;
  double plies = 0.0;
  rep.cover_factor = 1e300;
  for (int k = 0; k < std::max(2, stations); ++k) {
    const double sc = s0 + (s1 - s0) * k / (std::max(2, stations) - 1);
    // The section loop in n bins of theta: each bin's length along the loop.
    std::vector<Vec3> loop_pts(n + 1);
    for (int i = 0; i <= n; ++i) loop_pts[i] = surface.point(sc, 2.0 * M_PI * i / n);
    std::vector<double> bin(n);
    double loop = 0.0;
    for (int i = 0; i < n; ++i) loop += bin[i] = (loop_pts[i + 1] - loop_pts[i]).norm();
    StationCoverage st;
    st.station = sc;
    st.loop_length = loop;
    std::array<std::vector<int>, 2> stack{std::vector<int>(n, 0), std::vector<int>(n, 0)};
    double band_length = 0.0;
    std::array<double, 2> fam_length = {0.0, 0.0};
    for (std::size_t j = 0; j + 1 < s.size(); ++j) {
      if (!pts[j] || !pts[j + 1] || (s[j] < sc) == (s[j + 1] < sc)) continue;
      const double w = (sc - s[j]) / (s[j + 1] - s[j]);
      const Vec3 p = (1 - w) * pts[j]->position + w * pts[j + 1]->position;
      double ps = 0.0, pth = 0.0, pd = 0.0;
      surface.locate(p, &ps, &pth, &pd);
      // The trace of a band of width B on the loop: B over the sine of the fibre's angle to it.
      const int c = ((static_cast<int>(std::floor(pth / (2 * M_PI) * n)) % n) + n) % n;
      const Vec3 tau = (loop_pts[c + 1] - loop_pts[c]).normalized();
      const Vec3 nu = surface.normal(sc, 2.0 * M_PI * (c + 0.5) / n).cross(tau);
      const double ca = std::max(1e-6, std::abs(pts[j]->tangent.dot(nu)));
      const double width = std::min(loop, band_width / ca);
      const int fam = s[j + 1] > s[j] ? 0 : 1;
      ++st.bands[fam];
      fam_length[fam] += width;
      band_length += width;
      ++stack[fam][c];
      // Walk both ways from the centre bin until half the trace is laid each side.
      double fwd = 0.5 * bin[c], back = 0.5 * bin[c];
      for (int i = 1; i < n && fwd < 0.5 * width; ++i) {
        const int b = (c + i) % n;
        ++stack[fam][b];
        fwd += bin[b];
      }
      for (int i = 1; i < n && back < 0.5 * width; ++i) {
        const int b = ((c - i) % n + n) % n;
        ++stack[fam][b];
        back += bin[b];
      }
    }
    close_station(stack, &bin, loop, band_length, fam_length, &st, &rep, &plies);
  }
  rep.mean_plies = plies / rep.stations.size();
  return rep;
}

}  // namespace windplan
