// An independent reader for the tests: loads a URDF with libsdformat, whose URDF-to-SDF
// conversion is the one Gazebo runs, and prints what it keeps. Exit 0 when there is no error.
//   ERROR <message>
//   SENSOR <name> <type> <link>
#include <iostream>
#include <sdf/sdf.hh>

int main(int argc, char **argv) {
  if (argc != 2) {
    std::cerr << "usage: urdf2sdf FILE.urdf\n";
    return 2;
  }
  sdf::Root root;
  sdf::Errors errors = root.Load(argv[1]);
  for (const auto &e : errors) std::cout << "ERROR " << e.Message() << "\n";
  const sdf::Model *model = root.Model();
  if (!model) {
    std::cout << "ERROR no model\n";
    return 1;
  }
  for (uint64_t i = 0; i < model->LinkCount(); ++i) {
    const sdf::Link *link = model->LinkByIndex(i);
    for (uint64_t j = 0; j < link->SensorCount(); ++j) {
      const sdf::Sensor *s = link->SensorByIndex(j);
      std::cout << "SENSOR " << s->Name() << " " << s->TypeStr() << " " << link->Name() << "\n";
    }
  }
  return errors.empty() ? 0 : 1;
}
