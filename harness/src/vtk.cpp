#include "modalbench/harness/vtk.hpp"

#include <fmt/format.h>

#include <cctype>
#include <filesystem>
#include <numbers>
#include <stdexcept>

#include "modalbench/harness/files.hpp"

namespace modalbench {

namespace {

std::string safe(const std::string& s) {
  std::string o;
  for (char c : s) o += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
  return o;
}

std::string array(const std::string& name, int components, const std::vector<double>& v) {
  std::string out = fmt::format("<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">\n",
                                name, components);
  for (std::size_t i = 0; i < v.size(); ++i) out += fmt::format("{:.12g}{}", v[i], (i + 1) % 12 == 0 ? "\n" : " ");
  return out + "\n</DataArray>\n";
}

/// A beam's or plate's sample points (x, y) as points in space (z = 0).
std::vector<std::array<double, 3>> in_space(const std::vector<std::array<double, 2>>& pts) {
  std::vector<std::array<double, 3>> out;
  for (const auto& p : pts) out.push_back({p[0], p[1], 0.0});
  return out;
}

std::string grid(const std::vector<std::array<double, 3>>& pts, const std::vector<std::vector<long>>& cells,
                 int cell_type, const std::string& point_data) {
  std::vector<double> xyz;
  for (const auto& p : pts) xyz.insert(xyz.end(), {p[0], p[1], p[2]});
  std::string conn, offs, types;
  long off = 0;
  for (const auto& c : cells) {
    for (long i : c) conn += fmt::format("{} ", i);
    off += static_cast<long>(c.size());
    offs += fmt::format("{} ", off);
    types += fmt::format("{} ", cell_type);
  }
  return fmt::format(
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "<UnstructuredGrid>\n<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n<Points>\n{}</Points>\n"
      "<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">{}</DataArray>\n"
      "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">{}</DataArray>\n"
      "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">{}</DataArray>\n</Cells>\n"
      "<PointData>\n{}</PointData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n",
      pts.size(), cells.size(), array("Points", 3, xyz), conn, offs, types, point_data);
}

}  // namespace

std::vector<std::string> write_vtk(const Scene& scene, const std::string& backend, const Result& r,
                                   const std::string& dir) {
  if (r.mode_shapes.empty() && r.deflections.empty())
    throw std::invalid_argument("--vtk: nothing to export: the scene requests no shapes ([request] shapes) and no probes");
  make_output_dir(dir);
  std::vector<std::string> written;
  const std::string stem = safe(scene.name) + "_" + safe(backend);
  if (!r.mode_shapes.empty()) {
    const auto& ms = r.mode_shapes;
    const std::size_t np = ms.points.size();
    // Cells: a polyline's segments along a beam, quads on a plate's grid (x fastest).
    std::vector<std::vector<long>> cells;
    int type = 3;  // VTK_LINE
    if (scene.is_beam()) {
      for (std::size_t i = 0; i + 1 < np; ++i) cells.push_back({static_cast<long>(i), static_cast<long>(i + 1)});
    } else {
      type = 9;  // VTK_QUAD
      const long nx = scene.request.shapes->nx, ny = scene.request.shapes->ny;
      for (long j = 0; j + 1 < ny; ++j)
        for (long i = 0; i + 1 < nx; ++i)
          cells.push_back({j * nx + i, j * nx + i + 1, (j + 1) * nx + i + 1, (j + 1) * nx + i});
    }
    std::string data;
    for (std::size_t k = 0; k < ms.values.size(); ++k) {
      const double w = r.frequencies_rad_s[k];
      const std::string label = fmt::format("mode {} ({:.6g} rad_s, {:.6g} Hz)", k + 1, w, w / (2 * std::numbers::pi));
      std::vector<double> disp(3 * np, 0.0);
      for (std::size_t c = 0; c < ms.components.size(); ++c) {
        const int d = ms.components[c];
        if (d < 3)
          for (std::size_t p = 0; p < np; ++p) disp[3 * p + static_cast<std::size_t>(d)] = ms.values[k][c][p];
      }
      data += array(label + " displacement", 3, disp);
      for (std::size_t c = 0; c < ms.components.size(); ++c)
        if (ms.components[c] >= 3) data += array(label + " " + component_name(ms.components[c]), 1, ms.values[k][c]);
    }
    const std::string path = (std::filesystem::path(dir) / (stem + "_modes.vtu")).string();
    write_text_file(path, grid(in_space(ms.points), cells, type, data));
    written.push_back(path);
  }
  if (!r.deflections.empty()) {
    std::vector<std::array<double, 3>> pts;
    std::vector<double> disp, rot;
    std::vector<std::vector<long>> cells;
    for (const auto& d : r.deflections) {
      cells.push_back({static_cast<long>(pts.size())});
      // A frame's probe is a point in space (its position holds x and z only).
      pts.push_back(d.probe.empty() ? std::array<double, 3>{d.position[0], d.position[1], 0.0} : d.point);
      disp.insert(disp.end(), {d.u, d.v, d.w});
      rot.insert(rot.end(), {d.theta_x, d.theta_y, d.theta_z});
    }
    const std::string path = (std::filesystem::path(dir) / (stem + "_statics.vtu")).string();
    write_text_file(path, grid(pts, cells, 1, array("static displacement", 3, disp) + array("static rotation", 3, rot)));
    written.push_back(path);
  }
  return written;
}

}  // namespace modalbench
