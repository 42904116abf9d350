// OpenVDB grids behind grid_io.h's C interface (Museth 2013, "VDB:
// High-resolution sparse volumes with dynamic topology"). Exceptions never
// cross into C: every entry point catches them and reports an ss_error that
// names the file.
extern "C" {
#include "subsurf/grid_io.h"
}

#include <openvdb/openvdb.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <mutex>
#include <string>

namespace {

void initialise() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

openvdb::GridBase::Ptr find_grid(const openvdb::GridPtrVecPtr &grids, const std::string &name,
                                 bool float_grid) {
  openvdb::GridBase::Ptr first;
  for (const auto &g : *grids) {
    bool is_float = g->isType<openvdb::FloatGrid>();
    bool is_vec = g->isType<openvdb::Vec3SGrid>();
    if ((float_grid && !is_float) || (!float_grid && !is_vec)) {
      continue;
    }
    if (g->getName() == name) {
      return g;
    }
    if (!first && float_grid) {
      first = g;
    }
  }
  return first;
}

ss_status read_vdb(const char *path, ss_grid **out, ss_error *err) {
  initialise();
  openvdb::io::File file(path);
  file.open();
  openvdb::GridPtrVecPtr grids = file.getGrids();
  file.close();
  auto density = openvdb::gridPtrCast<openvdb::FloatGrid>(find_grid(grids, "density", true));
  if (!density) {
    return ss_error_set(err, SS_ERR_PARSE,
                        "%s: no float grid (expected a FloatGrid, ideally "
                        "named \"density\")",
                        path);
  }
  auto axis = openvdb::gridPtrCast<openvdb::Vec3SGrid>(find_grid(grids, "axis", false));
  if (!density->transform().isLinear()) {
    return ss_error_set(err, SS_ERR_PARSE, "%s: grid '%s' has a non-linear transform", path,
                        density->getName().c_str());
  }
  openvdb::CoordBBox box = density->evalActiveVoxelBoundingBox();
  if (box.empty()) {
    return ss_error_set(err, SS_ERR_PARSE, "%s: grid '%s' has no active voxels", path,
                        density->getName().c_str());
  }
  openvdb::Coord dim = box.dim();
  int n[3] = {dim.x(), dim.y(), dim.z()};
  // The voxels' outer faces in world space: index coordinates run from
  // min - 0.5 to max + 0.5 (OpenVDB puts values at integer coordinates).
  openvdb::Vec3d lo = density->indexToWorld(box.min().asVec3d() - openvdb::Vec3d(0.5));
  openvdb::Vec3d hi = density->indexToWorld(box.max().asVec3d() + openvdb::Vec3d(0.5));
  ss_grid *g = nullptr;
  ss_status st = ss_grid_create(n, ss_vec3_make(lo.x(), lo.y(), lo.z()),
                                ss_vec3_make(hi.x(), hi.y(), hi.z()), axis != nullptr, &g, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "%s: ", path);
    return st == SS_ERR_INVALID_ARGUMENT ? SS_ERR_PARSE : st;
  }
  auto dacc = density->getConstAccessor();
  openvdb::Vec3SGrid::ConstAccessor aacc =
      (axis ? axis : openvdb::Vec3SGrid::create())->getConstAccessor();
  for (int k = 0; k < n[2]; ++k) {
    for (int j = 0; j < n[1]; ++j) {
      for (int i = 0; i < n[0]; ++i) {
        openvdb::Coord c = box.min() + openvdb::Coord(i, j, k);
        int64_t v = ss_grid_index(g, i, j, k);
        g->density[v] = dacc.getValue(c);
        if (axis) {
          openvdb::Vec3d w = density->indexToWorld(c);
          openvdb::Vec3s a = aacc.getValue(openvdb::Coord::round(axis->worldToIndex(w)));
          double l = a.length();
          if (!std::isfinite(l) || (l == 0.0 && g->density[v] > 0.0f)) {
            ss_grid_destroy(g);
            return ss_error_set(err, SS_ERR_PARSE,
                                "%s: voxel (%d, %d, %d): the axis must be "
                                "finite and non-zero where the density is positive",
                                path, i, j, k);
          }
          ss_grid_set_axis(
              g, v, l > 0.0 ? ss_vec3_make(a.x(), a.y(), a.z()) : ss_vec3_make(0.0, 0.0, 1.0));
        }
      }
    }
  }
  if ((st = ss_grid_finish(g, err)) != SS_OK) {
    ss_error_prefix(err, "%s: ", path);
    ss_grid_destroy(g);
    return SS_ERR_PARSE;
  }
  *out = g;
  return SS_OK;
}

ss_status write_vdb(const char *path, const ss_grid *g, ss_error *err) {
  initialise();
  double h = (g->hi.x - g->lo.x) / g->n[0];
  for (int a = 1; a < 3; ++a) {
    double ha = (ss_vec3_component(g->hi, a) - ss_vec3_component(g->lo, a)) / g->n[a];
    if (std::fabs(ha - h) > 1e-9 * h) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "%s: OpenVDB needs cubic voxels, the grid's "
                          "are %g along x and %g along %c",
                          path, h, ha, "xyz"[a]);
    }
  }
  // Voxel (i, j, k) at index coordinate (i, j, k), its centre at
  // lo + (i + 1/2) h: a uniform scale and a translation.
  auto xf = openvdb::math::Transform::createLinearTransform(h);
  xf->postTranslate(openvdb::Vec3d(g->lo.x, g->lo.y, g->lo.z) + openvdb::Vec3d(0.5 * h));
  auto density = openvdb::FloatGrid::create(0.0f);
  density->setName("density");
  density->setTransform(xf);
  openvdb::Vec3SGrid::Ptr axis;
  if (g->axis) {
    axis = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    axis->setName("axis");
    axis->setTransform(xf->copy());
  }
  auto dacc = density->getAccessor();
  openvdb::Vec3SGrid::Accessor aacc = (axis ? axis : openvdb::Vec3SGrid::create())->getAccessor();
  for (int k = 0; k < g->n[2]; ++k) {
    for (int j = 0; j < g->n[1]; ++j) {
      for (int i = 0; i < g->n[0]; ++i) {
        int64_t v = ss_grid_index(g, i, j, k);
        openvdb::Coord c(i, j, k);
        // Every voxel active, zeros too, so that the active box is the grid's.
        dacc.setValueOn(c, g->density[v]);
        if (axis) {
          ss_vec3 a = ss_grid_axis_of(g, v);
          aacc.setValueOn(c, openvdb::Vec3s(a.x, a.y, a.z));
        }
      }
    }
  }
  openvdb::GridPtrVec grids;
  grids.push_back(density);
  if (axis) {
    grids.push_back(axis);
  }
  // Written beside the target and renamed, so that it appears complete or not at all.
  std::string tmp = std::string(path) + ".tmp-vdb";
  openvdb::io::File file(tmp);
  file.write(grids);
  file.close();
  if (std::rename(tmp.c_str(), path) != 0) {
    std::remove(tmp.c_str());
    return ss_error_set(err, SS_ERR_IO, "%s: cannot write", path);
  }
  return SS_OK;
}

} // namespace

extern "C" ss_status ss_grid_read_vdb(const char *path, ss_grid **out, ss_error *err) {
  *out = nullptr;
  try {
    return read_vdb(path, out, err);
  } catch (const std::exception &e) {
    return ss_error_set(err, SS_ERR_PARSE, "%s: not a readable OpenVDB file (%s)", path, e.what());
  }
}

extern "C" ss_status ss_grid_write_vdb(const char *path, const ss_grid *g, ss_error *err) {
  try {
    return write_vdb(path, g, err);
  } catch (const std::exception &e) {
    return ss_error_set(err, SS_ERR_IO, "%s: cannot write OpenVDB file (%s)", path, e.what());
  }
}
