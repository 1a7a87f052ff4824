#include "solver/io/xdmf.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace sph {

std::string polyvertex_dataset(std::uint64_t count) {
  return "/xdmf/polyvertex_" + std::to_string(count);
}

void write_xdmf(const std::string& path, const std::string& h5_name,
                const std::vector<SnapshotEntry>& snapshots, const std::vector<XdmfField>& fields) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error("cannot write " + tmp);
    out << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
        << "<Xdmf Version=\"3.0\">\n <Domain>\n"
        << "  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (const auto& s : snapshots) {
      char time[64];
      std::snprintf(time, sizeof time, "%.17g", s.time);
      const std::string n = std::to_string(s.count);
      out << "   <Grid Name=\"" << s.group.substr(s.group.rfind('/') + 1)
          << "\" GridType=\"Uniform\">\n"
          << "    <Time Value=\"" << time << "\"/>\n"
          << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n
          << "\" NodesPerElement=\"1\">\n"
          << "     <DataItem Dimensions=\"" << n
          << "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" << h5_name << ":"
          << polyvertex_dataset(s.count) << "</DataItem>\n"
          << "    </Topology>\n"
          << "    <Geometry GeometryType=\"XYZ\">\n"
          << "     <DataItem Dimensions=\"" << n
          << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5_name << ":"
          << s.group << "/position</DataItem>\n"
          << "    </Geometry>\n";
      for (const auto& f : fields) {
        out << "    <Attribute Name=\"" << f.name << "\" AttributeType=\""
            << (f.components == 1 ? "Scalar" : "Vector") << "\" Center=\"Node\">\n"
            << "     <DataItem Dimensions=\"" << n << (f.components == 1 ? "" : " 3")
            << "\" NumberType=\"" << f.number_type << "\" Precision=\"" << f.precision
            << "\" Format=\"HDF\">" << h5_name << ":" << s.group << "/" << f.name << "</DataItem>\n"
            << "    </Attribute>\n";
      }
      out << "   </Grid>\n";
    }
    out << "  </Grid>\n </Domain>\n</Xdmf>\n";
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace sph
