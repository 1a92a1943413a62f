#include "state_log.h"

#include <cstring>
#include <fstream>

namespace demo {

std::string writeStateFile(const std::string& path, const std::vector<PaneState>& panes,
                           const std::vector<Overlay>& overlays, long long frames, bool paused) {
  std::ofstream out(path);
  if (!out) return "cannot write state log '" + path + "'";
  out.precision(17);
  out << "# particle-demo state at exit; format in demos/gui/state_log.h\n";
  out << "frame," << frames << "\npaused," << (paused ? 1 : 0) << "\n";
  for (std::size_t k = 0; k < panes.size(); ++k) {
    const Simulation& sim = *panes[k].simulation;
    const particles::ParticleSystem& s = sim.system();
    int springs = 0;
    for (const auto& f : s.forceObjects()) springs += std::strcmp(f->type(), "mouse-spring") == 0;
    out << "pane," << k << "," << panes[k].sceneLabel << "," << sim.integratorName() << "," << sim.dt() << ","
        << s.time() << "," << sim.steps() << "," << (sim.divergedAt() ? 1 : 0) << "," << springs << ","
        << s.totalEnergy() << "," << s.maxConstraintError() << "\n";
    const ViewTransform& v = panes[k].view;
    out << "view," << k << "," << v.pane.x << "," << v.pane.y << "," << v.pane.width << "," << v.pane.height << ","
        << v.worldMin.x() << "," << v.worldMin.y() << "," << v.worldMax.x() << "," << v.worldMax.y() << "\n";
    for (int i = 0; i < s.size(); ++i) {
      const Eigen::Vector2d x = s.position(i), u = s.velocity(i);
      out << "particle," << k << "," << i << "," << x.x() << "," << x.y() << "," << u.x() << "," << u.y() << ","
          << s.masses()[i] << "," << (s.pinned(i) ? 1 : 0) << "\n";
    }
    for (const particles::Collider& c : s.colliders()) {
      Eigen::Vector2d lo, hi;  // a bounded collider's bounding box; a half-plane has none
      if (c.bounds(lo, hi)) out << "wall," << k << "," << lo.x() << "," << lo.y() << "," << hi.x() << "," << hi.y() << "\n";
    }
  }
  for (const Overlay& o : overlays)
    out << "overlay," << o.kind << "," << o.rect.x << "," << o.rect.y << "," << o.rect.width << "," << o.rect.height
        << "\n";
  return out ? "" : "error writing state log '" + path + "'";
}

}  // namespace demo
