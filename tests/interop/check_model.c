/* A model service call (request/reply) with GRAVITY_FORCES. */
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#include "interop.h"
#include "model.h"

/* The request/reply mapping of wbi (dds/include/wbi/dds/rpc.hpp): two plain
   topics; client_id + seq in the request, echoed in the reply. client_id is the
   GUID of the client's reply reader in 32 hex digits, which lets the server
   hold a request until its reply writer has matched that reader. */
static void guid_hex(const dds_guid_t* guid, char* text) {
  static const char digits[] = "0123456789abcdef";
  for (int i = 0; i < 16; ++i) {
    text[2 * i] = digits[guid->v[i] >> 4];
    text[2 * i + 1] = digits[guid->v[i] & 0xF];
  }
  text[32] = '\0';
}

void check_model(dds_entity_t participant, const Options* options) {
  /* wbi.request_reply: best effort, volatile; the client resends. */
  const dds_entity_t requests = writer(
      participant, topic(participant, &wbi_msg_ModelRequest_desc, options->robot, "model/request"),
      qos(DDS_RELIABILITY_BEST_EFFORT, DDS_DURABILITY_VOLATILE, 64));
  const dds_entity_t replies = reader(
      participant, topic(participant, &wbi_msg_ModelReply_desc, options->robot, "model/reply"),
      qos(DDS_RELIABILITY_BEST_EFFORT, DDS_DURABILITY_VOLATILE, 64));
  const dds_time_t deadline = deadline_after(options->timeout_s);
  wait_matched(participant, requests, true, "model request", deadline);
  wait_matched(participant, replies, false, "model reply", deadline);

  dds_guid_t guid;
  check_dds(dds_get_guid(replies, &guid), "reply reader guid");
  wbi_msg_ModelRequest request;
  memset(&request, 0, sizeof request);
  guid_hex(&guid, request.client_id);
  request.seq = 1;
  snprintf(request.robot, sizeof request.robot, "%s", options->robot);
  request.state.base_pose.orientation.w = 1.0;
  double zeros[wbi_msg_MAX_JOINTS] = {0};
  const uint32_t n = (uint32_t)options->gravity_joints;
  request.state.q = (dds_sequence_double){n, n, (double*)options->gravity_at, false};
  request.state.dq = (dds_sequence_double){n, n, zeros, false};
  request.state.gravity = (wbi_msg_Vector3){0.0, 0.0, -9.81};
  wbi_msg_OperationRequest operation = {.operation = wbi_msg_GRAVITY_FORCES};
  request.operations = (dds_sequence_wbi_msg_OperationRequest){1, 1, &operation, false};

  const dds_entity_t waitset = data_waitset(participant, &replies, 1);
  const dds_time_t sent = dds_time();
  dds_duration_t resend = DDS_MSECS(2);
  for (;;) {
    check_dds(dds_write(requests, &request), "write model request");
    const dds_time_t resend_at = dds_time() + resend;
    resend = resend * 2 > DDS_MSECS(100) ? DDS_MSECS(100) : resend * 2;
    while (dds_time() < resend_at) {
      void* samples[kTakeBatch] = {NULL};
      dds_sample_info_t infos[kTakeBatch];
      const dds_return_t count = dds_take(replies, samples, infos, kTakeBatch, kTakeBatch);
      check_dds(count, "take model reply");
      for (int i = 0; i < count; ++i) {
        const wbi_msg_ModelReply* reply = samples[i];
        if (!infos[i].valid_data || strcmp(reply->client_id, request.client_id) != 0 ||
            reply->seq != request.seq) {
          continue; /* another client's reply, or a probe's */
        }
        if (reply->error[0] != '\0') {
          fail("model: the service answered with an error: %s", reply->error);
        }
        if (reply->results._length != 1 ||
            reply->results._buffer[0].operation != wbi_msg_GRAVITY_FORCES) {
          fail("model: %" PRIu32 " results, expected one GRAVITY_FORCES", reply->results._length);
        }
        const wbi_msg_OperationResult* result = &reply->results._buffer[0];
        printf("model: GRAVITY_FORCES %" PRIu32 " x %" PRIu32 " in %.1f ms (server %.1f us)\n",
               result->rows, result->cols, (double)(dds_time() - sent) * 1e-6,
               (double)reply->compute_ns * 1e-3);
        printf("gravity_forces:");
        for (uint32_t k = 0; k < result->data._length; ++k) {
          printf(" %.17g", result->data._buffer[k]);
        }
        printf("\n");
        dds_return_loan(replies, samples, count);
        dds_delete(waitset);
        dds_delete(requests);
        dds_delete(replies);
        return;
      }
      if (count > 0) {
        dds_return_loan(replies, samples, count);
      }
      if (dds_time() > deadline) {
        fail("model: no reply within %.0f s", options->timeout_s);
      }
      dds_waitset_wait_until(waitset, NULL, 0, resend_at);
    }
  }
}
