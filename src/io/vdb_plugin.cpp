// The OpenVDB plugin (vdb_plugin.h; Museth 2013, "VDB: High-resolution
// sparse volumes with dynamic topology"). Exceptions never cross into C:
// every entry point catches them and reports an ss_error.
#include "io/vdb_plugin.h"

#include <openvdb/openvdb.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <string>

namespace {

ss_status fail(ss_error *err, ss_status status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

ss_status fail(ss_error *err, ss_status status, const char *fmt, ...) {
  err->status = status;
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(err->message, sizeof err->message, fmt, ap);
  va_end(ap);
  return status;
}

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

ss_status read_vdb(const char *path, int64_t max_voxels, ss_vdb_grid *out, ss_error *err) {
  initialise();
  openvdb::io::File file(path);
  file.open();
  openvdb::GridPtrVecPtr grids = file.getGrids();
  file.close();
  auto density = openvdb::gridPtrCast<openvdb::FloatGrid>(find_grid(grids, "density", true));
  if (!density) {
    return fail(err, SS_ERR_PARSE,
                "no float grid (expected a FloatGrid, ideally named \"density\")");
  }
  auto axis = openvdb::gridPtrCast<openvdb::Vec3SGrid>(find_grid(grids, "axis", false));
  if (!density->transform().isLinear()) {
    return fail(err, SS_ERR_PARSE, "grid '%s' has a non-linear transform",
                density->getName().c_str());
  }
  openvdb::CoordBBox box = density->evalActiveVoxelBoundingBox();
  if (box.empty()) {
    return fail(err, SS_ERR_PARSE, "grid '%s' has no active voxels", density->getName().c_str());
  }
  openvdb::Coord dim = box.dim();
  int64_t count = (int64_t)dim.x() * dim.y() * dim.z();
  if (count > max_voxels) {
    return fail(err, SS_ERR_PARSE,
                "grid '%s' spans %d x %d x %d voxels: at most %lld are supported",
                density->getName().c_str(), dim.x(), dim.y(), dim.z(), (long long)max_voxels);
  }
  // The voxels' outer faces in world space: index coordinates run from
  // min - 0.5 to max + 0.5 (OpenVDB puts values at integer coordinates).
  openvdb::Vec3d lo = density->indexToWorld(box.min().asVec3d() - openvdb::Vec3d(0.5));
  openvdb::Vec3d hi = density->indexToWorld(box.max().asVec3d() + openvdb::Vec3d(0.5));
  float *d = static_cast<float *>(std::malloc((size_t)count * sizeof(float)));
  float *a = axis ? static_cast<float *>(std::malloc((size_t)count * 3 * sizeof(float))) : nullptr;
  if (!d || (axis && !a)) {
    std::free(d);
    std::free(a);
    return fail(err, SS_ERR_NO_MEMORY, "out of memory for %lld voxels", (long long)count);
  }
  auto dacc = density->getConstAccessor();
  openvdb::Vec3SGrid::ConstAccessor aacc =
      (axis ? axis : openvdb::Vec3SGrid::create())->getConstAccessor();
  int64_t v = 0;
  for (int k = 0; k < dim.z(); ++k) {
    for (int j = 0; j < dim.y(); ++j) {
      for (int i = 0; i < dim.x(); ++i, ++v) {
        openvdb::Coord c = box.min() + openvdb::Coord(i, j, k);
        d[v] = dacc.getValue(c);
        if (axis) {
          openvdb::Vec3d w = density->indexToWorld(c);
          openvdb::Vec3s s = aacc.getValue(openvdb::Coord::round(axis->worldToIndex(w)));
          for (int m = 0; m < 3; ++m) {
            a[3 * v + m] = s[m];
          }
        }
      }
    }
  }
  *out = ss_vdb_grid{
      {dim.x(), dim.y(), dim.z()}, {lo.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), hi.z()}, d, a};
  return SS_OK;
}

ss_status write_vdb(const char *path, const ss_vdb_grid *g) {
  initialise();
  double h = (g->hi[0] - g->lo[0]) / g->n[0];
  // Voxel (i, j, k) at index coordinate (i, j, k), its centre at
  // lo + (i + 1/2) h: a uniform scale and a translation.
  auto xf = openvdb::math::Transform::createLinearTransform(h);
  xf->postTranslate(openvdb::Vec3d(g->lo[0], g->lo[1], g->lo[2]) + openvdb::Vec3d(0.5 * h));
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
  int64_t v = 0;
  for (int k = 0; k < g->n[2]; ++k) {
    for (int j = 0; j < g->n[1]; ++j) {
      for (int i = 0; i < g->n[0]; ++i, ++v) {
        openvdb::Coord c(i, j, k);
        // Every voxel active, zeros too, so that the active box is the grid's.
        dacc.setValueOn(c, g->density[v]);
        if (axis) {
          const float *a = g->axis + 3 * v;
          aacc.setValueOn(c, openvdb::Vec3s(a[0], a[1], a[2]));
        }
      }
    }
  }
  openvdb::GridPtrVec grids;
  grids.push_back(density);
  if (axis) {
    grids.push_back(axis);
  }
  openvdb::io::File file(path);
  file.write(grids);
  file.close();
  return SS_OK;
}

} // namespace

extern "C" ss_status ss_vdb_plugin_read(const char *path, int64_t max_voxels, ss_vdb_grid *out,
                                        ss_error *err) {
  try {
    return read_vdb(path, max_voxels, out, err);
  } catch (const std::exception &e) {
    return fail(err, SS_ERR_PARSE, "not a readable OpenVDB file (%s)", e.what());
  }
}

extern "C" ss_status ss_vdb_plugin_write(const char *path, const ss_vdb_grid *g, ss_error *err) {
  try {
    return write_vdb(path, g);
  } catch (const std::exception &e) {
    return fail(err, SS_ERR_IO, "cannot write OpenVDB file (%s)", e.what());
  }
}
