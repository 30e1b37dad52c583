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

std::string data_item(const std::string& h5_file_name, const std::string& dataset, std::size_t rows,
                      int columns, const std::string& number_type, int precision) {
  return "<DataItem Dimensions=\"" + dimensions(rows, columns) + "\" NumberType=\"" + number_type +
         "\" Precision=\"" + std::to_string(precision) + "\" Format=\"HDF\">" +
         xml_escape(h5_file_name) + ":" + xml_escape(dataset) + "</DataItem>";
}

std::string time_text(double time) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", time);  // round-trips a double
  return buffer;
}

}  // namespace

std::string xdmf_document(const std::string& h5_file_name, const std::vector<XdmfFrame>& frames) {
  std::string x;
  x += "<?xml version=\"1.0\" ?>\n";
  x += "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n";
  x += "<Xdmf Version=\"2.0\">\n";
  x += " <Domain>\n";
  x += "  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const XdmfFrame& frame : frames) {
    const std::string name = frame.group.substr(frame.group.find_last_of('/') + 1);
    const std::size_t n = frame.n_points;
    x += "   <Grid Name=\"frame_" + name + "\" GridType=\"Uniform\">\n";
    x += "    <Time Value=\"" + time_text(frame.time) + "\"/>\n";
    // One vertex cell per particle. The connectivity is explicit: ParaView's Xdmf3 readers make
    // no cells from a Polyvertex topology without it (only its XDMF (2) reader does).
    x += "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + std::to_string(n) +
         "\" NodesPerElement=\"1\">\n";
    x += "     " + data_item(h5_file_name, frame.group + "/" + frame.vertices, n, 1, "Int", 4) +
         "\n";
    x += "    </Topology>\n";
    x += "    <Geometry GeometryType=\"XYZ\">\n";
    x += "     " + data_item(h5_file_name, frame.group + "/" + frame.geometry, n, 3, "Float", 8) +
         "\n";
    x += "    </Geometry>\n";
    for (const XdmfField& field : frame.fields) {
      x += "    <Attribute Name=\"" + xml_escape(field.name) + "\" AttributeType=\"" +
           field.attribute_type + "\" Center=\"Node\">\n";
      x += "     " +
           data_item(h5_file_name, frame.group + "/" + field.name, n, field.components,
                     field.number_type, field.precision) +
           "\n";
      x += "    </Attribute>\n";
    }
    x += "   </Grid>\n";
  }
  x += "  </Grid>\n";
  x += " </Domain>\n";
  x += "</Xdmf>\n";
  return x;
}

void write_xdmf(const std::string& path, const std::string& h5_file_name,
                const std::vector<XdmfFrame>& frames) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(temporary + ": cannot open for writing");
    out << xdmf_document(h5_file_name, frames);
    out.flush();
    if (!out) throw std::runtime_error(temporary + ": write failed");
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) throw std::runtime_error(path + ": cannot replace (" + error.message() + ")");
}

}  // namespace duet
