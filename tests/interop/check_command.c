/* A POSITION command that the robot applies, seen on its sensors, and counted
 * on its status. */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "interop.h"
#include "sensors.h"
#include "status.h"

/* Takes sensor samples until `joint` is within `tolerance` of `target` (any
 * sample when target is NaN) or the deadline; returns its last position, and
 * in *reached whether it got there. */
static double latest_position(dds_entity_t r, dds_entity_t waitset, uint32_t joint,
                              dds_time_t deadline, double target, double tolerance, bool* reached) {
  double position = NAN;
  *reached = false;
  for (;;) {
    void* samples[kTakeBatch] = {NULL};
    dds_sample_info_t infos[kTakeBatch];
    const dds_return_t n = dds_take(r, samples, infos, kTakeBatch, kTakeBatch);
    check_dds(n, "take sensors");
    for (int i = 0; i < n; ++i) {
      const wbi_msg_SensorSample* s = samples[i];
      if (infos[i].valid_data && joint < s->encoder_position._length) {
        position = s->encoder_position._buffer[joint];
      }
    }
    if (n > 0) {
      dds_return_loan(r, samples, n);
    }
    if (!isnan(position) && (isnan(target) || fabs(position - target) <= tolerance)) {
      *reached = true;
      return position;
    }
    if (!wait_data(waitset, deadline)) {
      return position;
    }
  }
}

void check_command(dds_entity_t participant, const Options* options, uint32_t joints,
                   char joint_names[][wbi_msg_MAX_NAME + 1]) {
  if (options->joint < 0 || (uint32_t)options->joint >= joints) {
    fail("--joint %d: the robot has %" PRIu32 " joints", options->joint, joints);
  }
  const uint32_t joint = (uint32_t)options->joint;
  const dds_entity_t sensors =
      reader(participant, topic(participant, &wbi_msg_SensorSample_desc, options->robot, "sensors"),
             qos(DDS_RELIABILITY_RELIABLE, DDS_DURABILITY_TRANSIENT_LOCAL, 1));
  const dds_entity_t waitset = data_waitset(participant, &sensors, 1);
  /* wbi.command: reliable and volatile; the robot's reader is reliable, so a
     best-effort writer would not match it. */
  const dds_entity_t commands = writer(
      participant, topic(participant, &wbi_msg_ActuatorCommand_desc, options->robot, "commands"),
      qos(DDS_RELIABILITY_RELIABLE, DDS_DURABILITY_VOLATILE, 8));
  dds_time_t deadline = deadline_after(options->timeout_s);
  wait_matched(participant, commands, true, "commands", deadline);

  bool reached = false;
  const double start = latest_position(sensors, waitset, joint, deadline, NAN, 0.0, &reached);
  if (!reached) {
    fail("command: no sensor sample within %.0f s", options->timeout_s);
  }
  const double target = start + options->move;

  uint16_t joint_index = (uint16_t)joint;
  wbi_msg_ControlMode mode = wbi_msg_POSITION;
  double reference = target;
  wbi_msg_ActuatorCommand command;
  memset(&command, 0, sizeof command);
  snprintf(command.header.robot, sizeof command.header.robot, "%s", options->robot);
  command.header.stamp_ns = dds_time();
  command.header.seq = 0;
  snprintf(command.controller, sizeof command.controller, "cyclone_interop");
  command.joints = (dds_sequence_unsigned_short){1, 1, &joint_index, false};
  command.modes = (dds_sequence_wbi_msg_ControlMode){1, 1, &mode, false};
  command.references = (dds_sequence_double){1, 1, &reference, false};
  const dds_time_t sent = dds_time();
  check_dds(dds_write(commands, &command), "write command");

  deadline = deadline_after(options->timeout_s);
  const double last = latest_position(sensors, waitset, joint, deadline, target,
                                      options->reach_tolerance, &reached);
  if (!reached) {
    fail("command: %s POSITION %.4f rad not reached within %.0f s (at %.4f, from %.4f)",
         joint_names[joint], target, options->timeout_s, last, start);
  }
  printf("command: %s POSITION %+.3f rad (%.4f -> %.4f) reached within %.1f mrad after %.2f s\n",
         joint_names[joint], options->move, start, target, options->reach_tolerance * 1e3,
         (double)(dds_time() - sent) * 1e-9);
  dds_delete(waitset);
  dds_delete(commands);
  dds_delete(sensors);
}

static uint64_t counter(const wbi_msg_ComponentStatus* s, const char* name) {
  for (uint32_t i = 0; i < s->counters._length; ++i) {
    if (strcmp(s->counters._buffer[i].name, name) == 0) {
      return s->counters._buffer[i].value;
    }
  }
  return UINT64_MAX;
}

/* After the command: the robot's component reports it ACTIVE, with the
   command counted as accepted and none rejected. */
void check_status(dds_entity_t participant, const Options* options) {
  /* wbi.status is best effort: a reliable reader would not match. */
  const dds_entity_t r =
      reader(participant, topic(participant, &wbi_msg_ComponentStatus_desc, NULL, "wbi/status"),
             qos(DDS_RELIABILITY_BEST_EFFORT, DDS_DURABILITY_VOLATILE, 16));
  const dds_entity_t waitset = data_waitset(participant, &r, 1);
  const dds_time_t deadline = deadline_after(options->timeout_s);
  for (;;) {
    void* samples[kTakeBatch] = {NULL};
    dds_sample_info_t infos[kTakeBatch];
    const dds_return_t n = dds_take(r, samples, infos, kTakeBatch, kTakeBatch);
    check_dds(n, "take status");
    for (int i = 0; i < n; ++i) {
      const wbi_msg_ComponentStatus* s = samples[i];
      if (!infos[i].valid_data || strcmp(s->instance, options->component) != 0) {
        continue;
      }
      const uint64_t accepted = counter(s, "accepted_commands");
      const uint64_t rejected = counter(s, "rejected_commands");
      if (s->state != wbi_msg_ACTIVE || accepted == 0 || accepted == UINT64_MAX) {
        continue; /* an earlier status, from before the command */
      }
      if (rejected != 0) {
        fail("status: '%s' rejected %" PRIu64 " command(s): %s", s->instance, rejected,
             s->last_error);
      }
      printf("status: '%s' (%s) ACTIVE, %u counters, accepted_commands %" PRIu64
             ", rejected_commands %" PRIu64 "\n",
             s->instance, s->type, s->counters._length, accepted, rejected);
      dds_return_loan(r, samples, n);
      dds_delete(waitset);
      dds_delete(r);
      return;
    }
    if (n > 0) {
      dds_return_loan(r, samples, n);
    }
    if (!wait_data(waitset, deadline)) {
      fail(
          "status: no status of '%s' on wbi/status, ACTIVE and counting the command as "
          "accepted, within %.0f s",
          options->component, options->timeout_s);
    }
  }
}
