// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The pairs of links a robot's SRDF (MoveIt's semantic description) says may touch (issue #60):
// its <disable_collisions link1="..." link2="..."/> elements, which a motion check leaves
// unchecked as it does adjacent links (RobotBody's may_touch).

#include <string>
#include <utility>
#include <vector>

namespace lmk {

using LinkPair = std::pair<std::string, std::string>;

/// The <disable_collisions> pairs of the SRDF text `xml`, in document order. `what` names it in
/// errors. Throws lmk::Error for text that is no XML, a root that is not <robot>, or an element
/// without both links.
std::vector<LinkPair> srdf_disabled_collisions(const std::string& xml, const std::string& what);

/// The same, read from the file `path`; throws lmk::Error naming a file that cannot be read.
std::vector<LinkPair> srdf_disabled_collisions_file(const std::string& path);

}  // namespace lmk
