"""Reading a recording gives the published values: wbi_test_write_recording
(write_test_recording.cpp) writes real CDR samples of four wbi types with the
C++ MCAP writer, uncompressed, zstd and lz4; wbi.Recording decodes them from
the omgidl schemas in the file, and the values match the helper's formulas
(repeated here). Also: wbi-plot writes a PNG, truncated and corrupt files."""

import importlib.util
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy as np

import support
import wbi
from wbi.mcap import McapError, McapReader

HELPER = support.BINARY_DIR / "tests" / "wbi_test_write_recording"


def lz4_available():
    return importlib.util.find_spec("lz4") is not None


class RecordingValues(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="wbi_python_recording_")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def write(self, compression):
        path = os.path.join(self.dir, f"known_{compression}.mcap")
        result = support.run([HELPER, path, compression], timeout_s=60)
        self.assertEqual(result.returncode, 0, result.stderr)
        return path

    def check(self, path):
        rec = wbi.Recording(path)
        self.assertEqual(rec.topics, ["wbi/arm/commands", "wbi/arm/description",
                                      "wbi/arm/sensors", "wbi/arm/signals/pd", "wbi/arm/state",
                                      "wbi/arm/status"])
        self.assertFalse(rec.truncated)
        self.assertAlmostEqual(rec.duration_s, 0.049)

        state = rec.topic("wbi/arm/state")
        self.assertEqual(state.type_name, "wbi::msg::StateEstimate")
        k = np.arange(50)
        self.assertEqual(len(state), 50)
        np.testing.assert_array_equal(state.log_time_ns, 1_000_000_000 + k * 1_000_000)
        np.testing.assert_array_equal(state.publish_time_ns, state.log_time_ns + 10)
        np.testing.assert_allclose(state.t, k * 1e-3)
        np.testing.assert_array_equal(state["header.seq"], k)
        np.testing.assert_array_equal(state["header.stamp_ns"], k * 1_000_000)
        self.assertTrue(all(robot == "arm" for robot in state["header.robot"]))
        j = np.arange(7)
        np.testing.assert_array_equal(state["q"], 0.1 * k[:, None] + j[None, :])
        np.testing.assert_array_equal(state["dq"], -0.01 * k[:, None] * (j[None, :] + 1))
        self.assertEqual(state["ddq"].shape, (50, 0))
        # tau = [k] on even k, empty on odd k: padded with NaN
        np.testing.assert_array_equal(state["tau"][::2, 0], k[::2])
        self.assertTrue(np.isnan(state["tau"][1::2, 0]).all())
        np.testing.assert_array_equal(state["base_pose.position.x"], 0.5 * k)
        np.testing.assert_array_equal(state["base_pose.position.z"], 1.5 * k)
        np.testing.assert_array_equal(state["base_pose.orientation.w"], np.ones(50))
        i = np.arange(6)
        np.testing.assert_array_equal(state["base_velocity"], k[:, None] + i[None, :] / 10.0)
        np.testing.assert_array_equal(state["base_acceleration"], np.tile(-i, (50, 1)))
        np.testing.assert_array_equal(state["force_torque.force.x"],
                                      np.stack([k, k + 1], axis=1))
        np.testing.assert_array_equal(state["force_torque.torque.z"],
                                      np.stack([-k, -k - 1], axis=1))
        np.testing.assert_array_equal(state["warnings"], k % 3)

        commands = rec.topic("wbi/arm/commands")
        k = np.arange(20)
        np.testing.assert_array_equal(commands.log_time_ns,
                                      1_000_000_000 + 2 * k * 1_000_000 + 500_000)
        np.testing.assert_array_equal(commands["tick"], k)
        np.testing.assert_array_equal(commands["source_stamp_ns"], -k)
        np.testing.assert_array_equal(commands["joints"], np.tile(np.arange(7), (20, 1)))
        names = commands.enum_names("modes")
        modes = commands["modes"]
        self.assertTrue((np.vectorize(names.get)(modes[:, 0]) == "POSITION").all())
        self.assertTrue((np.vectorize(names.get)(modes[:, 1:]) == "TORQUE").all())
        np.testing.assert_array_equal(commands["references"],
                                      k[:, None] + 0.5 * np.arange(7)[None, :])
        self.assertTrue(all(name == "pd" for name in commands["controller"]))

        status = rec.topic("wbi/arm/status")
        self.assertEqual(list(status["last_error"]), ["", "", "boom"])
        self.assertEqual(status.enum_names("state")[status["state"][0]], "ACTIVE")
        np.testing.assert_array_equal(status["iterations"], [0, 1000, 2000])
        self.assertEqual(list(status["counters.name"][2]), ["rejected", "late"])
        np.testing.assert_array_equal(status["counters.value"], [[0, 0], [1, 2], [2, 4]])

        sensors = rec.topic("wbi/arm/sensors")
        k = np.arange(10)
        np.testing.assert_array_equal(sensors.log_time_ns, 1_000_000_000 + 5 * k * 1_000_000 + 1)
        np.testing.assert_array_equal(sensors["encoder_position"],
                                      np.arange(7)[None, :] - k[:, None])
        np.testing.assert_array_equal(sensors["imus.angular_velocity.x"], k[:, None])
        np.testing.assert_array_equal(sensors["imus.linear_acceleration.z"], np.full((10, 1), 9.81))
        self.assertEqual(sensors["force_torque.wrench.force.x"].shape, (10, 0))

        # One time base: the state's q at the sensor samples' times (zero-order hold).
        held = state.at(sensors.t, "q")
        np.testing.assert_array_equal(held, state["q"][5 * k])
        self.assertTrue(np.isnan(state.at([-1.0], "q")).all())
        return rec

    def test_uncompressed(self):
        self.check(self.write("none"))

    def test_zstd(self):
        self.check(self.write("zstd"))

    def test_lz4(self):
        path = self.write("lz4")
        if not lz4_available():
            with self.assertRaisesRegex(McapError, "python3-lz4"):
                wbi.Recording(path)
            return
        self.check(path)

    def test_messages_in_log_time_order_across_chunks(self):
        reader = McapReader(self.write("none"))
        times = [message.log_time for message in reader.messages()]
        self.assertEqual(len(times), 50 + 20 + 3 + 10 + 1 + 5)
        self.assertEqual(times, sorted(times))

    def test_unknown_topic_and_field_are_named(self):
        rec = wbi.Recording(self.write("none"))
        with self.assertRaisesRegex(wbi.RecordingError, "no messages on topic 'wbi/x'"):
            rec.topic("wbi/x")
        with self.assertRaisesRegex(wbi.RecordingError, "no field 'qq'; it has: .*q"):
            rec.topic("wbi/arm/state")["qq"]

    def test_truncated_file_reads_up_to_the_cut(self):
        path = self.write("none")
        with open(path, "rb") as file:
            data = file.read()
        cut = os.path.join(self.dir, "cut.mcap")
        with open(cut, "wb") as file:
            file.write(data[:len(data) // 2])
        rec = wbi.Recording(cut)
        self.assertTrue(rec.truncated)
        self.assertIn("truncated", rec.warnings[0])
        state = rec.topic("wbi/arm/state")
        self.assertGreater(len(state), 0)
        self.assertLess(len(state), 50)
        np.testing.assert_array_equal(state["header.seq"], np.arange(len(state)))

    def test_corrupt_file_names_the_byte(self):
        with open(self.write("none"), "rb") as file:
            data = bytearray(file.read())
        corrupt = os.path.join(self.dir, "corrupt.mcap")
        with open(corrupt, "wb") as file:
            file.write(b"not an mcap file")
        with self.assertRaisesRegex(McapError, "corrupt.mcap: byte 0: not an MCAP file"):
            wbi.Recording(corrupt)
        # flip a byte inside the first chunk's records: its CRC no longer matches
        at = 8
        while data[at] != 0x06:  # walk the records (opcode, u64 length) to the first Chunk
            at += 9 + int.from_bytes(data[at + 1:at + 9], "little")
        at += 9 + 40 + 100  # past the chunk's own fields, into its records
        data[at] ^= 0xFF
        with open(corrupt, "wb") as file:
            file.write(bytes(data))
        with self.assertRaises(McapError) as caught:
            wbi.Recording(corrupt)
        self.assertRegex(str(caught.exception),
                         r"corrupt.mcap: byte \d+: Chunk record: CRC mismatch")

    def test_plot_names_the_elements(self):
        from wbi.plot import element_names
        rec = wbi.Recording(self.write("zstd"))
        signals = rec.topic("wbi/arm/signals/pd")
        np.testing.assert_array_equal(signals["values"], np.stack([np.arange(5),
                                                                   -2 * np.arange(5)], axis=1))
        self.assertEqual(element_names(rec, signals, "values"), ["error", "effort"])
        joints = [f"joint_{j}" for j in range(1, 8)]
        self.assertEqual(element_names(rec, rec.topic("wbi/arm/state"), "q"), joints)
        self.assertEqual(element_names(rec, rec.topic("wbi/arm/sensors"), "encoder_position"),
                         joints)
        self.assertIsNone(element_names(rec, rec.topic("wbi/arm/state"), "base_velocity"))
        self.assertIsNone(element_names(rec, rec.topic("wbi/arm/state"), "header.seq"))

    def test_plot_writes_a_png(self):
        path = self.write("zstd")
        png = os.path.join(self.dir, "scope.png")
        result = support.run([support.BINARY_DIR / "bin" / "wbi-plot", path, "wbi/arm/state", "q",
                              "dq[2]", "header.seq", "-o", png], timeout_s=120)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("wrote", result.stdout)
        self.assertIn("50 messages", result.stdout)
        with open(png, "rb") as file:
            self.assertEqual(file.read(8), b"\x89PNG\r\n\x1a\n")
        bad = support.run([support.BINARY_DIR / "bin" / "wbi-plot", path, "wbi/arm/state",
                           "dq[9]", "-o", png], timeout_s=60)
        self.assertEqual(bad.returncode, 1)
        self.assertIn("index 9 is out of range", bad.stderr)
        both = support.run([support.BINARY_DIR / "bin" / "wbi-plot", path, "wbi/arm/signals/pd",
                            "values[1,0]", "-o", png], timeout_s=120)
        self.assertEqual(both.returncode, 0, both.stderr)
        listing = support.run([support.BINARY_DIR / "bin" / "wbi-plot", path, "--list"],
                              timeout_s=60)
        self.assertEqual(listing.returncode, 0, listing.stderr)
        self.assertIn("wbi/arm/state  (wbi::msg::StateEstimate, 50 messages)", listing.stdout)

    def test_plot_list_into_a_closed_pipe_is_not_an_error(self):
        # `wbi-plot run.mcap --list | head -n 3`: the reader is gone before the listing ends.
        # Its read end is closed before wbi-plot starts, so every write meets the closed pipe.
        path = self.write("zstd")
        read_end, write_end = os.pipe()
        os.close(read_end)
        try:
            result = subprocess.run([str(support.BINARY_DIR / "bin" / "wbi-plot"), path, "--list"],
                                    stdout=write_end, stderr=subprocess.PIPE, text=True,
                                    timeout=60, check=False)
        finally:
            os.close(write_end)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stderr, "")


class IdlSubset(unittest.TestCase):
    def test_constants_typedefs_arrays_and_errors(self):
        from wbi.omgidl import IdlError, parse_idl, resolve
        types = parse_idl("""
            module a { const unsigned long N = 2 * 3; typedef string<N> Name;
              module b { struct S { Name name; double m[N][2]; sequence<long, N> s; }; }; };
            """)
        s = resolve(types, "a::b::S")
        self.assertEqual([name for name, _ in s.members], ["name", "m", "s"])
        self.assertEqual(s.members[1][1].dims, (6, 2))
        with self.assertRaisesRegex(IdlError, "line 1: 'union' is not supported"):
            parse_idl("union U switch (long) { case 1: long x; };")
        with self.assertRaisesRegex(IdlError, "unknown type 'Missing'"):
            parse_idl("struct T { Missing m; };")


if __name__ == "__main__":
    unittest.main(argv=sys.argv, verbosity=2)
