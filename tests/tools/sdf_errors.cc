// An independent check for the tests: loads an SDF file with libsdformat's sdf::Root::Load
// (the call Gazebo Sim makes) and prints every error it reports, then resolves what
// gz-sim resolves when it creates the entities, every sensor's pose
// (SemanticPose().Resolve) and every joint axis (JointAxis::ResolveXyz), and prints the
// errors of those too. model:// URIs are looked up in the folders of
// GZ_SIM_RESOURCE_PATH. One line per error:
//   LOAD <CODE> <line or 0> <message on one line>
//   SENSOR <CODE> <model>::<link>::<sensor> <message on one line>
//   AXIS <CODE> <model>::<joint> <message on one line>
// Exit 0 when no error was printed, 1 otherwise, 2 on bad usage.
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <sdf/sdf.hh>

static const char *code_name(sdf::ErrorCode code) {
  switch (code) {
#define NAME(c) \
  case sdf::ErrorCode::c: return #c;
    NAME(NONE) NAME(FILE_READ) NAME(DUPLICATE_NAME) NAME(RESERVED_NAME)
    NAME(ATTRIBUTE_MISSING) NAME(ATTRIBUTE_INVALID) NAME(ATTRIBUTE_DEPRECATED)
    NAME(ATTRIBUTE_INCORRECT_TYPE) NAME(ELEMENT_MISSING) NAME(ELEMENT_INVALID)
    NAME(ELEMENT_DEPRECATED) NAME(ELEMENT_INCORRECT_TYPE) NAME(URI_INVALID)
    NAME(URI_LOOKUP) NAME(DIRECTORY_NONEXISTANT) NAME(MODEL_CANONICAL_LINK_INVALID)
    NAME(MODEL_WITHOUT_LINK) NAME(NESTED_MODELS_UNSUPPORTED) NAME(LINK_INERTIA_INVALID)
    NAME(JOINT_CHILD_LINK_INVALID) NAME(JOINT_PARENT_LINK_INVALID)
    NAME(JOINT_PARENT_SAME_AS_CHILD) NAME(FRAME_ATTACHED_TO_INVALID)
    NAME(FRAME_ATTACHED_TO_CYCLE) NAME(FRAME_ATTACHED_TO_GRAPH_ERROR)
    NAME(POSE_RELATIVE_TO_INVALID) NAME(POSE_RELATIVE_TO_CYCLE)
    NAME(POSE_RELATIVE_TO_GRAPH_ERROR) NAME(STRING_READ) NAME(MODEL_PLACEMENT_FRAME_INVALID)
    NAME(VERSION_DEPRECATED) NAME(MERGE_INCLUDE_UNSUPPORTED)
#undef NAME
    default: return "OTHER";
  }
}

static std::string one_line(std::string text) {
  for (char &c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

static int resolve(const sdf::Model *model, const std::string &prefix) {
  int bad = 0;
  for (uint64_t i = 0; i < model->JointCount(); ++i) {
    const sdf::Joint *joint = model->JointByIndex(i);
    for (unsigned int a = 0; a < 2; ++a) {
      const sdf::JointAxis *axis = joint->Axis(a);
      if (!axis) continue;
      ignition::math::Vector3d xyz;
      for (const auto &e : axis->ResolveXyz(xyz)) {
        std::cout << "AXIS " << code_name(e.Code()) << " " << prefix << joint->Name() << " "
                  << one_line(e.Message()) << "\n";
        ++bad;
      }
    }
  }
  for (uint64_t i = 0; i < model->LinkCount(); ++i) {
    const sdf::Link *link = model->LinkByIndex(i);
    for (uint64_t j = 0; j < link->SensorCount(); ++j) {
      const sdf::Sensor *s = link->SensorByIndex(j);
      ignition::math::Pose3d pose;
      for (const auto &e : s->SemanticPose().Resolve(pose)) {
        std::cout << "SENSOR " << code_name(e.Code()) << " " << prefix << link->Name()
                  << "::" << s->Name() << " " << one_line(e.Message()) << "\n";
        ++bad;
      }
    }
  }
  for (uint64_t i = 0; i < model->ModelCount(); ++i) {
    const sdf::Model *nested = model->ModelByIndex(i);
    bad += resolve(nested, prefix + nested->Name() + "::");
  }
  return bad;
}

int main(int argc, char **argv) {
  if (argc != 2) {
    std::cerr << "usage: sdf_errors FILE.sdf\n";
    return 2;
  }
  sdf::ParserConfig config;
  if (const char *paths = std::getenv("GZ_SIM_RESOURCE_PATH")) {
    std::stringstream in(paths);
    std::string dir;
    while (std::getline(in, dir, ':'))
      if (!dir.empty()) config.AddURIPath("model://", dir);
  }
  sdf::Root root;
  const sdf::Errors errors = root.Load(argv[1], config);
  int bad = 0;
  for (const auto &e : errors) {
    std::cout << "LOAD " << code_name(e.Code()) << " " << e.LineNumber().value_or(0) << " "
              << one_line(e.Message()) << "\n";
    ++bad;
  }
  if (const sdf::Model *model = root.Model()) bad += resolve(model, model->Name() + "::");
  for (uint64_t w = 0; w < root.WorldCount(); ++w) {
    const sdf::World *world = root.WorldByIndex(w);
    for (uint64_t i = 0; i < world->ModelCount(); ++i) {
      const sdf::Model *model = world->ModelByIndex(i);
      bad += resolve(model, model->Name() + "::");
    }
  }
  return bad == 0 ? 0 : 1;
}
