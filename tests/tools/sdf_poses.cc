// An independent reader for the tests: loads an SDF file with libsdformat (sdf::Root, the
// reader Gazebo Sim runs) and prints where it puts every link and sensor, each pose resolved
// with SemanticPose().Resolve(), nested models included. model:// URIs are looked up in the
// folders of GZ_SIM_RESOURCE_PATH. Exit 0 when libsdformat reports no error.
//   ERROR <message>
//   LINK <model> <frame> <scoped link> x y z r00 r01 r02 r10 r11 r12 r20 r21 r22
//   SENSOR <model> <frame> <scoped link>::<sensor> x y z r00 ... r22
//   MASS <model> inertial <scoped link> mass ixx ixy ixz iyy iyz izz  (Link::Inertial())
// <frame> is "model" (the pose in the top model's frame) or "world" (world files only).
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <sdf/sdf.hh>

using Pose3 = ignition::math::Pose3d;

static void print(const char *kind, const std::string &model, const char *frame,
                  const std::string &name, const Pose3 &p) {
  const auto R = ignition::math::Matrix3d(p.Rot());
  std::printf("%s %s %s %s %.17g %.17g %.17g", kind, model.c_str(), frame, name.c_str(),
              p.Pos().X(), p.Pos().Y(), p.Pos().Z());
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) std::printf(" %.17g", R(i, j));
  std::printf("\n");
}

static void error(const sdf::Errors &errors) {
  for (const auto &e : errors) std::cout << "ERROR " << e.Message() << "\n";
}

// Every link and sensor of `model`, whose frame is X_top_model in the top model's frame
// (and X_world_top in the world's), named with `prefix` (the nested models' scope).
static int walk(const sdf::Model *model, const std::string &top, const std::string &prefix,
                const Pose3 &X_top_model, const Pose3 *X_world_top) {
  int bad = 0;
  for (uint64_t i = 0; i < model->LinkCount(); ++i) {
    const sdf::Link *link = model->LinkByIndex(i);
    Pose3 X_model_link;
    sdf::Errors errors = link->SemanticPose().Resolve(X_model_link, "__model__");
    error(errors);
    bad += errors.size();
    const Pose3 X_top_link = X_top_model * X_model_link;
    const std::string name = prefix + link->Name();
    print("LINK", top, "model", name, X_top_link);
    const auto &inertial = link->Inertial();
    const auto I = inertial.MassMatrix().Moi();
    std::printf("MASS %s inertial %s %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", top.c_str(),
                name.c_str(), inertial.MassMatrix().Mass(), I(0, 0), I(0, 1), I(0, 2), I(1, 1),
                I(1, 2), I(2, 2));
    if (X_world_top) print("LINK", top, "world", name, *X_world_top * X_top_link);
    for (uint64_t j = 0; j < link->SensorCount(); ++j) {
      const sdf::Sensor *s = link->SensorByIndex(j);
      Pose3 X_model_sensor;
      errors = s->SemanticPose().Resolve(X_model_sensor, "__model__");
      error(errors);
      bad += errors.size();
      const Pose3 X_top_sensor = X_top_model * X_model_sensor;
      print("SENSOR", top, "model", name + "::" + s->Name(), X_top_sensor);
      if (X_world_top) print("SENSOR", top, "world", name + "::" + s->Name(), *X_world_top * X_top_sensor);
    }
  }
  for (uint64_t i = 0; i < model->ModelCount(); ++i) {
    const sdf::Model *nested = model->ModelByIndex(i);
    Pose3 X_model_nested;
    sdf::Errors errors = nested->SemanticPose().Resolve(X_model_nested, "__model__");
    error(errors);
    bad += errors.size();
    bad += walk(nested, top, prefix + nested->Name() + "::", X_top_model * X_model_nested, X_world_top);
  }
  return bad;
}

int main(int argc, char **argv) {
  if (argc != 2) {
    std::cerr << "usage: sdf_poses FILE.sdf\n";
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
  sdf::Errors errors = root.Load(argv[1], config);
  error(errors);
  int bad = errors.size();
  if (const sdf::Model *model = root.Model()) {
    bad += walk(model, model->Name(), "", Pose3::Zero, nullptr);
  }
  for (uint64_t w = 0; w < root.WorldCount(); ++w) {
    const sdf::World *world = root.WorldByIndex(w);
    for (uint64_t i = 0; i < world->ModelCount(); ++i) {
      const sdf::Model *model = world->ModelByIndex(i);
      Pose3 X_world_model;
      errors = model->SemanticPose().Resolve(X_world_model, "world");
      error(errors);
      bad += errors.size();
      bad += walk(model, model->Name(), "", Pose3::Zero, &X_world_model);
    }
  }
  return bad == 0 ? 0 : 1;
}
