// `simulate --schedule`. See schedule_run.h.
#include "schedule_run.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <utility>
#include <variant>

namespace nonsmooth_sim::simulate {
namespace {

std::string Where(const scene_io::ScheduledEvent& e) {
  char time[32];
  std::snprintf(time, sizeof time, "%g", e.time);
  return "schedule line " + std::to_string(e.line) + " (at " + time + " s): ";
}

}  // namespace

ScheduleRunner::ScheduleRunner(std::vector<scene_io::ScheduledEvent> events,
                               scene_io::UrdfSceneOptions options)
    : events_(std::move(events)) {
  options.ground = false;  // the world has its ground already
  for (const scene_io::ScheduledEvent& e : events_) {
    models_.emplace_back();
    const auto* spawn = std::get_if<scene_io::SpawnEvent>(&e.what);
    if (spawn == nullptr) continue;
    try {
      models_.back() = scene_io::LoadUrdfFile(spawn->urdf_path, options).scene;
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument(Where(e) + error.what());
    }
  }
}

void ScheduleRunner::Before(world::World* world, double t, double dt) {
  for (; next_ < events_.size() && events_[next_].time < t + dt; ++next_) {
    const scene_io::ScheduledEvent& e = events_[next_];
    try {
      if (const auto* spawn = std::get_if<scene_io::SpawnEvent>(&e.what)) {
        world->Spawn(spawn->model, models_[next_], "",
                     world::Pose{spawn->position, spawn->orientation}, spawn->urdf_path);
      } else if (const auto* wrench = std::get_if<scene_io::WrenchEvent>(&e.what)) {
        world::WrenchRequest request;
        request.body = wrench->body;
        request.force = wrench->force;
        request.torque = wrench->torque;
        request.point = wrench->point;
        request.start = e.time;
        request.duration = wrench->duration;
        world->ApplyWrench(request);
      } else if (const auto* state = std::get_if<scene_io::StateEvent>(&e.what)) {
        world->SetModelState(state->model, "", world::Pose{state->position, state->orientation},
                             world::Twist{state->linear_velocity, state->angular_velocity});
      } else {
        world->Delete(std::get<scene_io::DeleteEvent>(e.what).model);
      }
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument(Where(e) + error.what());
    }
  }
  world->ApplyScheduledWrenches(dt);
}

std::vector<std::string> ScheduleRunner::BodyColumns(const Scene& start) const {
  std::vector<std::string> names;
  for (const RigidBody& b : start.bodies) names.push_back(b.name);
  for (std::size_t k = 0; k < events_.size(); ++k) {
    const auto* spawn = std::get_if<scene_io::SpawnEvent>(&events_[k].what);
    if (spawn == nullptr) continue;
    for (const RigidBody& b : models_[k].bodies) {
      const std::string name = spawn->model + "/" + b.name;
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }
  }
  return names;
}

}  // namespace nonsmooth_sim::simulate
