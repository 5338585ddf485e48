# golden/expected holds generated code as text to compare with (its tests are not ours to run).
collect_ignore_glob = ["golden/*"]
