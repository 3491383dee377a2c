// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/srdf.h"

#include <tinyxml2.h>

#include <fstream>
#include <sstream>

#include "lmk/geometry/error.h"

namespace lmk {

std::vector<LinkPair> srdf_disabled_collisions(const std::string& xml, const std::string& what) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS)
    throw Error(what + ": not an SRDF: " + (doc.ErrorStr() ? doc.ErrorStr() : "unreadable XML"));
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (!robot || std::string(robot->Name()) != "robot")
    throw Error(what + ": not an SRDF: its root element is not <robot>");
  std::vector<LinkPair> pairs;
  for (const tinyxml2::XMLElement* e = robot->FirstChildElement("disable_collisions"); e;
       e = e->NextSiblingElement("disable_collisions")) {
    const char* a = e->Attribute("link1");
    const char* b = e->Attribute("link2");
    if (!a || !b || !*a || !*b)
      throw Error(what + ": a <disable_collisions> element (line " +
                  std::to_string(e->GetLineNum()) + ") lacks link1 or link2");
    pairs.emplace_back(a, b);
  }
  return pairs;
}

std::vector<LinkPair> srdf_disabled_collisions_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read the SRDF '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return srdf_disabled_collisions(text.str(), path);
}

}  // namespace lmk
