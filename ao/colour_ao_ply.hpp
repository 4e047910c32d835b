// Colour AO (the PMI paper's eq. 12; viewpoint colours (1 + direction) / 2) per vertex of PMI's
// object, as an ASCII PLY with vertex colours (`aosuite viewpoints --colour-ao`).
#pragma once

#include <filesystem>

#include "renderer/pmi/pmi_channel.hpp"

namespace aosuite::ao {

// `channel` computed with PmiSettings::colour; throws FileError when the file cannot be written.
void write_colour_ao(const std::filesystem::path& path, const renderer::PmiObject& object,
                     const renderer::PmiChannel& channel);

}  // namespace aosuite::ao
