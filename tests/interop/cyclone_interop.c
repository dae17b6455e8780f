/* A client of a running wbi robot written with Eclipse Cyclone DDS only: its
 * types come from the .idl files of idl/ through Cyclone's own idlc, it includes no wbi
 * header and links no Fast DDS. It is the proof that the IDL files are the
 * whole wire contract (idl/README.md, "Speaking wbi from another DDS").
 *
 *   wbi_interop_cyclone --robot arm [--domain N] [--samples 300] [--joint 0 --move 0.2]
 *                       [--gravity-at q1,...,qn] [--timeout 30]
 *
 * Checks, in order (one line each on stdout; a failure prints one line on
 * stderr and exits 1):
 *   description  wbi/<robot>/description (latched) names the joints;
 *   sensors      wbi/<robot>/sensors against wbi/<robot>/ground_truth, paired by
 *                header.seq: every encoder within --position-tolerance of q;
 *   state        wbi/<robot>/state against the ground truth, paired by
 *                header.stamp_ns (the estimate carries its sensor sample's stamp);
 *   command      a POSITION command on wbi/<robot>/commands moves one joint by
 *                --move rad, seen on the sensors;
 *   status       wbi/status of the robot's component (--component, default the
 *                robot name): ACTIVE, the command counted as accepted;
 *   model        with --gravity-at: GRAVITY_FORCES from the model service
 *                (wbi/<robot>/model/request and /reply), printed as
 *                "gravity_forces: g1 ... gn" for the caller to check.
 * The domain id: --domain, else WBI_DOMAIN_ID, else 0. Network settings come
 * from CYCLONEDDS_URI (cyclonedds_loopback.xml meets wbi's loopback-only
 * participants). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <dds/dds.h>
#include <dds/version.h>

#include "interop.h"

static double parse_number(const char* text, const char* option) {
  char* end = NULL;
  errno = 0;
  const double value = strtod(text, &end);
  if (errno != 0 || end == text || *end != '\0' || !isfinite(value)) {
    fail("%s: '%s' is not a number", option, text);
  }
  return value;
}

static int parse_list(const char* text, double* out, int capacity, const char* option) {
  int count = 0;
  char buffer[4096];
  if (strlen(text) >= sizeof buffer) {
    fail("%s: list too long", option);
  }
  strcpy(buffer, text);
  for (char* item = strtok(buffer, ","); item != NULL; item = strtok(NULL, ",")) {
    if (count == capacity) {
      fail("%s: more than %d values", option, capacity);
    }
    out[count++] = parse_number(item, option);
  }
  return count;
}

static Options parse_options(int argc, char** argv) {
  Options options = {.robot = NULL,
                     .component = NULL,
                     .domain = 0,
                     .samples = 300,
                     /* half an encoder count of the arm (2^14 counts per turn): the
                        sensor model rounds q to the nearest count */
                     .position_tolerance = M_PI / 16384.0 + 1e-9,
                     .joint = 0,
                     .move = 0.2,
                     .reach_tolerance = 0.01,
                     .timeout_s = 30.0,
                     .gravity_joints = 0};
  const char* domain = getenv("WBI_DOMAIN_ID");
  if (domain != NULL && *domain != '\0') {
    options.domain = (int)parse_number(domain, "WBI_DOMAIN_ID");
  }
  for (int i = 1; i < argc; ++i) {
    const char* option = argv[i];
    if (strcmp(option, "--help") == 0 || strcmp(option, "-h") == 0) {
      printf(
          "usage: wbi_interop_cyclone --robot NAME [--component INSTANCE] [--domain N]\n"
          "       [--samples N]\n"
          "       [--position-tolerance RAD] [--joint INDEX] [--move RAD]\n"
          "       [--reach-tolerance RAD] [--gravity-at q1,...,qn] [--timeout S]\n");
      exit(0);
    }
    if (i + 1 >= argc) {
      fail("%s needs a value (see --help)", option);
    }
    const char* value = argv[++i];
    if (strcmp(option, "--robot") == 0) {
      options.robot = value;
    } else if (strcmp(option, "--component") == 0) {
      options.component = value;
    } else if (strcmp(option, "--domain") == 0) {
      options.domain = (int)parse_number(value, option);
    } else if (strcmp(option, "--samples") == 0) {
      options.samples = (int)parse_number(value, option);
    } else if (strcmp(option, "--position-tolerance") == 0) {
      options.position_tolerance = parse_number(value, option);
    } else if (strcmp(option, "--joint") == 0) {
      options.joint = (int)parse_number(value, option);
    } else if (strcmp(option, "--move") == 0) {
      options.move = parse_number(value, option);
    } else if (strcmp(option, "--reach-tolerance") == 0) {
      options.reach_tolerance = parse_number(value, option);
    } else if (strcmp(option, "--timeout") == 0) {
      options.timeout_s = parse_number(value, option);
    } else if (strcmp(option, "--gravity-at") == 0) {
      options.gravity_joints = parse_list(value, options.gravity_at, wbi_msg_MAX_JOINTS, option);
    } else {
      fail("unknown option '%s' (see --help)", option);
    }
  }
  if (options.robot == NULL) {
    fail("--robot NAME is required (see --help)");
  }
  if (options.component == NULL) {
    options.component = options.robot;
  }
  if (options.samples < 1 || options.samples > kMaxSamples) {
    fail("--samples must be in [1, %d]", kMaxSamples);
  }
  return options;
}

int main(int argc, char** argv) {
  const Options options = parse_options(argc, argv);
  setvbuf(stdout, NULL, _IOLBF, 0);
  const dds_entity_t participant =
      dds_create_participant((dds_domainid_t)options.domain, NULL, NULL);
  check_dds(participant, "create participant");
  printf("cyclone dds %s, domain %d, robot '%s'\n", DDS_VERSION, options.domain, options.robot);

  char joint_names[wbi_msg_MAX_JOINTS][wbi_msg_MAX_NAME + 1];
  const uint32_t joints = check_description(participant, &options, joint_names);
  check_streams(participant, &options, joints);
  check_command(participant, &options, joints, joint_names);
  check_status(participant, &options);
  if (options.gravity_joints > 0) {
    check_model(participant, &options);
  }
  dds_delete(participant);
  printf("interop: every check passed\n");
  return 0;
}
