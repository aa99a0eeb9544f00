// In-memory shader files for tests of raykit/shader_source.hpp: a loader callback over a map, and
// the list of paths it was asked for (to check which includes the resolver reads).
#pragma once

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "raykit/shader_source.hpp"

struct MemFiles {
    std::map<std::string, std::string> files;
    std::vector<std::string> read;
    /// A loader over `files` that records every path asked for (capture: this object; keep it alive).
    raykit::ShaderLoader loader()
    {
        return [this](const std::string& path, std::string& text) {
            read.push_back(path);
            const auto it = files.find(path);
            if (it == files.end()) return false;
            text = it->second;
            return true;
        };
    }
    bool was_read(const std::string& p) const { return std::find(read.begin(), read.end(), p) != read.end(); }
};
