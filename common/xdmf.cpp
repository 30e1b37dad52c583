#include "common/xdmf.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace duet {

namespace {

/// Escape the characters XML does not allow in attribute values and text.
std::string xml_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string dimensions(std::size_t rows, int columns) {
  return columns == 1 ? std::to_string(rows) : std::to_string(rows) + " " + std::to_string(columns);
}

/// Dataset `dataset` at the root of the frame's file.
std::string data_item(const XdmfFrame& frame, const std::string& dataset, std::size_t rows,
                      int columns, const std::string& number_type, int precision) {
  return "<DataItem Dimensions=\"" + dimensions(rows, columns) + "\" NumberType=\"" + number_type +
         "\" Precision=\"" + std::to_string(precision) + "\" Format=\"HDF\">" +
         xml_escape(frame.file) + ":/" + xml_escape(dataset) + "</DataItem>";
}

std::string time_text(double time) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", time);  // round-trips a double
  return buffer;
}

}  // namespace

namespace {

/// Topology of `cells` cells of `per_cell` nodes from dataset `connectivity` of the frame.
std::string topology(const XdmfFrame& frame, const std::string& type,
                     const std::string& connectivity, std::size_t cells, int per_cell) {
  std::string x = "    <Topology TopologyType=\"" + type + "\" NumberOfElements=\"" +
                  std::to_string(cells) + "\" NodesPerElement=\"" + std::to_string(per_cell) +
                  "\">\n";
  x += "     " + data_item(frame, connectivity, cells, per_cell, "Int", 4) + "\n";
  x += "    </Topology>\n";
  return x;
}

std::string geometry(const XdmfFrame& frame, const std::string& dataset, std::size_t points) {
  return "    <Geometry GeometryType=\"XYZ\">\n     " +
         data_item(frame, dataset, points, 3, "Float", 8) + "\n    </Geometry>\n";
}

std::string point_fields(const XdmfFrame& frame) {
  std::string x;
  for (const XdmfField& field : frame.fields) {
    x += "    <Attribute Name=\"" + xml_escape(field.name) + "\" AttributeType=\"" +
         field.attribute_type + "\" Center=\"Node\">\n";
    x += "     " +
         data_item(frame, field.name, frame.n_points, field.components, field.number_type,
                   field.precision) +
         "\n";
    x += "    </Attribute>\n";
  }
  return x;
}

std::string grid_open(const std::string& prefix, const XdmfFrame& frame) {
  return "   <Grid Name=\"" + prefix + "_" + frame.name +
         "\" GridType=\"Uniform\">\n    <Time Value=\"" + time_text(frame.time) + "\"/>\n";
}

/// One temporal collection of the frames for which `grid` returns a grid ("" to skip).
template <typename Grid>
std::string collection(const std::string& name, const std::vector<XdmfFrame>& frames, Grid grid) {
  std::string body;
  for (const XdmfFrame& frame : frames) body += grid(frame);
  if (body.empty()) return "";
  return "  <Grid Name=\"" + name + "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n" +
         body + "  </Grid>\n";
}

}  // namespace

std::string xdmf_document(const std::vector<XdmfFrame>& frames) {
  std::string x;
  x += "<?xml version=\"1.0\" ?>\n";
  x += "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n";
  x += "<Xdmf Version=\"2.0\">\n";
  x += " <Domain>\n";
  // The particle grid is always written, even with no frames yet (an empty collection).
  x += "  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const XdmfFrame& frame : frames) {
    // One vertex cell per particle. The connectivity is explicit: ParaView's Xdmf3 readers make
    // no cells from a Polyvertex topology without it (only its XDMF (2) reader does).
    x += grid_open("frame", frame) +
         topology(frame, "Polyvertex", frame.vertices, frame.n_points, 1) +
         geometry(frame, frame.geometry, frame.n_points) + point_fields(frame) + "   </Grid>\n";
  }
  x += "  </Grid>\n";
  x += collection("boundaries", frames, [&](const XdmfFrame& frame) -> std::string {
    if (frame.n_boundary_segments == 0) return "";
    return grid_open("boundaries", frame) +
           topology(frame, "Polyline", "boundary_segments", frame.n_boundary_segments, 2) +
           geometry(frame, "boundary_points", frame.n_boundary_points) +
           "    <Attribute Name=\"boundary\" AttributeType=\"Scalar\" Center=\"Cell\">\n     " +
           data_item(frame, "boundary", frame.n_boundary_segments, 1, "Int", 4) +
           "\n    </Attribute>\n   </Grid>\n";
  });
  x += collection("mesh", frames, [&](const XdmfFrame& frame) -> std::string {
    if (frame.n_triangles == 0) return "";
    return grid_open("mesh", frame) +
           topology(frame, "Triangle", "triangles", frame.n_triangles, 3) +
           geometry(frame, frame.geometry, frame.n_points) + point_fields(frame) + "   </Grid>\n";
  });
  x += collection("surface", frames, [&](const XdmfFrame& frame) -> std::string {
    if (frame.n_surface_edges == 0) return "";
    return grid_open("surface", frame) +
           topology(frame, "Polyline", "surface_edges", frame.n_surface_edges, 2) +
           geometry(frame, frame.geometry, frame.n_points) + "   </Grid>\n";
  });
  x += " </Domain>\n";
  x += "</Xdmf>\n";
  return x;
}

void write_xdmf(const std::string& path, const std::vector<XdmfFrame>& frames) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(temporary + ": cannot open for writing");
    out << xdmf_document(frames);
    out.flush();
    if (!out) throw std::runtime_error(temporary + ": write failed");
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) throw std::runtime_error(path + ": cannot replace (" + error.message() + ")");
}

}  // namespace duet
