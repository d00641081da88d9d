#pragma once
// Readers of the values a scene file (docs/scene.md) is made of: vectors, rotations and time
// functions. Each fails with the YAML item's one-line "<file>:<line>:<col>: <item>: <problem>".

#include <Eigen/Core>

#include <string_view>

#include "core/yaml_node.h"
#include "mbs/time_function.h"

namespace flexmbs::mbs {

/// The length [m] under `key` of `node`, > 0; else InputError "<item>: <owner>: <value> m must be > 0"
/// (owner says whose length it is, e.g. "contact 'floor'").
double ReadPositiveLength(const YamlNode& node, std::string_view key, std::string_view owner);

/// A list of three finite numbers.
Eigen::Vector3d ReadVector3(const YamlNode& node);

/// A rotation `{axis: [x, y, z], angle: a}` (a in rad, about the axis, right-handed); the axis
/// must not be zero.
Eigen::Matrix3d ReadRotation(const YamlNode& node);

/// A time function: a number (constant) or one of
///   {ramp: {offset: a, slope: b}}                      a + b t
///   {polynomial: [c0, c1, ...]}                        sum c_k t^k
///   {harmonic: {amplitude: A, angular_frequency: w, phase: p, offset: c}}   A sin(w t + p) + c
///   {smooth_step: {t0: , f0: , t1: , f1: , order: cubic | quintic}}
///   {table: {times: [...], values: [...]}}             cubic spline
TimeFunctionPtr ReadTimeFunction(const YamlNode& node);

}  // namespace flexmbs::mbs
