"""The command line: demo, info, bench, overhead, and the scenes they share with the tests."""
