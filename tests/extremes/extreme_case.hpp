#pragma once
// One row of the extremes table: the scene a case writes, the render
// settings it changes, and the closed-form value its images must have.
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/image/image.hpp"
#include "tests/extremes/extreme_scenes.hpp"

namespace weft::test::extremes {

struct CaseSetup {
    explicit CaseSetup(const TempDir& d) : dir(d) {}
    const TempDir& dir;
    json scene = json::object();  // written to scene.json and rendered, unless input is set
    std::string input;            // another input to render (a bare mesh, say)
    std::string resolution = "4x4";
    int spp = 1;
    // Numeric parameters wanted at an extreme: applied to the techniques whose
    // table has the key, clamped into the table's [min, max].
    std::vector<std::pair<std::string, double>> extremes;
    // Parameters given as text, to techniques whose table has the key.
    std::vector<std::pair<std::string, std::string>> sets;
    // The case is about its parameters: techniques that have none of them skip it.
    bool parametersOnly = false;
    // Words of a refusal this case's content may draw (besides content a
    // technique does not render and the settings the case changed).
    std::vector<std::string> mayRefuseNaming;
    // Every technique must refuse the input, with a message holding this text.
    std::string mustRefuseWith;
    // A closed form the image of `technique` must match (ADD_FAILURE on a miss).
    std::function<void(const std::string& technique, const Image& image)> closedForm;
};

struct ExtremeCase {
    const char* name;
    void (*build)(CaseSetup&);
};

}  // namespace weft::test::extremes
