// The material-model registry (scene/MaterialModels.h) against the code it describes: every id
// below GPURT_MODEL_COUNT is one model, in id order, with a name of its own; each model's file is
// a file of glsl/common that material.h includes, and material.h dispatches on its id.
#include "scene/MaterialModels.h"

#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace gpurt {
namespace {

std::string readText(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(MaterialModels, EveryIdIsOneModelWithItsFileIncludedAndDispatched) {
    const std::vector<MaterialModelInfo>& models = materialModels();
    ASSERT_EQ(models.size(), size_t(GPURT_MODEL_COUNT));
    const std::string material = readText("glsl/common/material.h");
    ASSERT_FALSE(material.empty()) << "glsl/common/material.h (tests run in the project root)";
    const std::string ids = readText("glsl/common/material_models.h");
    std::set<std::string> names;
    for (size_t k = 0; k < models.size(); ++k) {
        const MaterialModelInfo& m = models[k];
        EXPECT_EQ(m.id, int(k));
        EXPECT_EQ(findMaterialModel(m.id), &m);
        EXPECT_TRUE(names.insert(std::string(m.name)).second) << m.name;
        EXPECT_FALSE(m.summary.empty()) << m.name;
        if (!m.source.empty()) {
            EXPECT_FALSE(readText("glsl/common/" + std::string(m.source)).empty()) << m.source;
            EXPECT_NE(material.find("#include \"" + std::string(m.source) + "\""), std::string::npos) << m.source;
        }
        // Its id's define, and a dispatch on it (every model but the classic one, the default).
        const std::string define = "#define GPURT_MODEL_";
        size_t at = ids.find(define);
        std::string macro;
        while (at != std::string::npos) {
            std::istringstream line(ids.substr(at + 8));
            std::string name;
            int value = -1;
            line >> name >> value;
            if (value == m.id && name != "GPURT_MODEL_COUNT") macro = name;
            at = ids.find(define, at + 1);
        }
        ASSERT_FALSE(macro.empty()) << m.name << ": no GPURT_MODEL_* define of id " << m.id;
        if (m.id != GPURT_MODEL_CLASSIC) {
            EXPECT_NE(material.find("m.model == " + macro), std::string::npos) << macro << " is not dispatched";
        }
    }
    EXPECT_EQ(findMaterialModel(GPURT_MODEL_COUNT), nullptr);
    EXPECT_EQ(findMaterialModel(-1), nullptr);
    for (const MaterialModelInfo& m : models)  // what a message about an unknown id lists
        EXPECT_NE(materialModelList().find(std::to_string(m.id) + " " + std::string(m.name)), std::string::npos);
}

}  // namespace
}  // namespace gpurt
