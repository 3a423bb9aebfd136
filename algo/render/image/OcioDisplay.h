#pragma once
/// Display encoding through OpenColorIO: linear radiance to display code values by a
/// config's display and view, as studios' pipelines do. The config is a file, else the one
/// $OCIO names, else CloudGraph's built-in config (builtinOcioConfig: linear Rec.709 scene
/// space; display sRGB with the views "ACES 1.0 - SDR Video", the ACES 1.0 RRT and sRGB
/// output transform from OpenColorIO's built-in transforms, and "Un-tone-mapped", the sRGB
/// curve alone; the names the ACES studio configs use).

#include <cstddef>
#include <memory>
#include <string>

namespace cg::algo {

/// Which transform: empty fields take the config's defaults (its default display, that
/// display's default view); the input is the colour space the pixels are in.
struct OcioChoice {
    std::string configFile;  ///< empty: $OCIO if set, else the built-in config
    std::string input = "Linear Rec.709 (sRGB)";
    std::string display;
    std::string view;
};

/// The text of the built-in config (OCIO v2).
const std::string& builtinOcioConfig();

/// The config file an OcioChoice with an empty configFile reads: $OCIO, or empty for the
/// built-in config.
std::string ocioConfigFromEnvironment();

class OcioDisplay {
public:
    /// Loads the config and builds the processor. Throws std::invalid_argument naming the
    /// config file, display, view or colour space that is not there.
    explicit OcioDisplay(const OcioChoice& choice);
    ~OcioDisplay();
    OcioDisplay(const OcioDisplay&) = delete;
    OcioDisplay& operator=(const OcioDisplay&) = delete;

    /// Transforms `pixels` RGB triples in place to display-encoded values (not clamped).
    /// Safe to call from several threads at once.
    void apply(float* rgb, std::size_t pixels) const;

    const std::string& display() const { return mDisplay; }
    const std::string& view() const { return mView; }

private:
    struct Processor;
    std::unique_ptr<Processor> mProcessor;
    std::string mDisplay, mView;
};

}  // namespace cg::algo
