"""wbi.DdsInterface joins as every wbi tool does (dds/README.md, "Joining a
deployment"): a deploy file, then the WBI_* environment, then the keyword
arguments (their precedence: tests/placement/test_join_options, same code);
mistakes name their source. No DDS traffic: each case fails before the
interface makes its participant."""

import os
import tempfile
import unittest

import wbi

URDF = os.path.join(os.environ.get("WBI_SOURCE_DIR", "."), "models", "arm7.urdf")


def join_error(**keywords):
    try:
        wbi.DdsInterface(robot="arm", urdf=URDF, **keywords)
    except ValueError as error:
        return str(error)
    return "(no error)"


class JoinTest(unittest.TestCase):
    def test_a_deploy_file_mistake_names_the_file_and_line(self):
        with tempfile.NamedTemporaryFile("w", suffix=".yaml") as deploy:
            deploy.write("processes: []\nnetwork: {discovery: broadcast}\n")
            deploy.flush()
            self.assertEqual(
                join_error(deploy=deploy.name),
                f"{deploy.name}:2: network.discovery: must be localhost, multicast, peers or "
                "server, got 'broadcast'")

    def test_the_environment_and_the_keywords_are_read(self):
        os.environ["WBI_DDS_DISCOVERY"] = "broadcast"
        try:
            self.assertEqual(join_error(),
                             "WBI_DDS_DISCOVERY: must be localhost, multicast, peers or server, "
                             "got 'broadcast'")
        finally:
            del os.environ["WBI_DDS_DISCOVERY"]
        self.assertEqual(join_error(discovery="wifi"),
                         "discovery: must be localhost, multicast, peers or server, got 'wifi'")

    def test_a_secured_deployment_needs_an_identity(self):
        with tempfile.TemporaryDirectory() as keys:
            self.assertIn("give identity=NAME", join_error(security=keys))


if __name__ == "__main__":
    unittest.main()
