#!/usr/bin/env python3
"""The summary tools/test.sh prints at the end: each stage's seconds, the 10 slowest tests, and the failing tests by
name.

  tools/test-report.py STAGES [--junit FILE]... [--results DIR]... [--slowest N]

STAGES: lines "name<TAB>seconds<TAB>exit status" (tools/test.sh writes them as each stage ends).
--junit: ctest's --output-junit files (one per ctest run): every ctest entry's seconds and outcome.
--results: folders of GoogleTest JSON reports (--gtest_output=json, one per ctest entry: tests/cmake/TestSuites.cmake).
A GoogleTest entry (a suite run in one process) is ranked by its tests, each with its own seconds; the other entries
(browser suites, scripts, the examples) as a whole.
"""
import argparse
import glob
import json
import os
import sys
import xml.etree.ElementTree as ElementTree


def seconds(text):
    try:
        return float(str(text).rstrip('s'))
    except ValueError:
        return 0.0


def read_stages(path):
    stages = []
    if os.path.exists(path):
        with open(path) as lines:
            for line in lines:
                fields = line.rstrip('\n').split('\t')
                if len(fields) == 3:
                    stages.append((fields[0], float(fields[1]), int(fields[2])))
    return stages


def read_gtest(folders):
    """(seconds, 'entry: Suite.Test', failed) for every test of every report, and the report names (entries)."""
    tests, entries = [], set()
    for folder in folders:
        for path in sorted(glob.glob(os.path.join(folder, '*.json'))):
            entry = os.path.splitext(os.path.basename(path))[0]
            try:
                with open(path) as report:
                    data = json.load(report)
            except (OSError, ValueError):
                continue
            entries.add(entry)
            prefix = entry.rsplit('.', 1)[0] if '.' in entry else entry
            for suite in data.get('testsuites', []):
                for test in suite.get('testsuite', []):
                    failed = bool(test.get('failures'))
                    name = '%s.%s' % (suite.get('name', '?'), test.get('name', '?'))
                    tests.append((seconds(test.get('time', 0)), '%s  (%s)' % (name, prefix), failed))
    return tests, entries


def read_junit(paths, gtest_entries):
    """(seconds, ctest name, outcome) for every ctest entry that is not a GoogleTest one, and every entry's outcome."""
    others, outcomes = [], []
    for path in paths:
        if not os.path.exists(path):
            continue
        try:
            root = ElementTree.parse(path).getroot()
        except ElementTree.ParseError:
            continue
        for case in root.iter('testcase'):
            name = case.get('name', '?')
            status = case.get('status', '')
            if case.find('failure') is not None or status == 'fail':
                outcome = 'failed'
            elif case.find('skipped') is not None or status in ('notrun', 'disabled'):
                outcome = 'not run'
            else:
                outcome = 'passed'
            outcomes.append((name, outcome))
            safe = ''.join(c if c.isalnum() or c in '_.-' else '_' for c in name)
            if safe not in gtest_entries:
                others.append((seconds(case.get('time', 0)), name, outcome))
    return others, outcomes


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('stages')
    parser.add_argument('--junit', action='append', default=[])
    parser.add_argument('--results', action='append', default=[])
    parser.add_argument('--slowest', type=int, default=10)
    args = parser.parse_args()

    stages = read_stages(args.stages)
    print('\n== tools/test.sh: seconds per stage ==')
    width = max([len(name) for name, _, _ in stages] + [5])
    for name, secs, status in stages:
        print('  %-*s %8.1f  %s' % (width, name, secs, 'ok' if status == 0 else 'FAILED (exit %d)' % status))
    print('  %-*s %8.1f' % (width, 'total', sum(secs for _, secs, _ in stages)))

    tests, gtest_entries = read_gtest(args.results)
    others, outcomes = read_junit(args.junit, gtest_entries)
    ranked = sorted([(secs, name) for secs, name, _ in tests] + [(secs, name) for secs, name, _ in others],
                    reverse=True)
    if ranked:
        print('\n== the %d slowest tests (GoogleTest tests one by one; other ctest entries whole) ==' % args.slowest)
        for secs, name in ranked[:args.slowest]:
            print('  %8.1f  %s' % (secs, name))

    failed_entries = [name for name, outcome in outcomes if outcome == 'failed']
    failed_tests = [name for _, name, failed in tests if failed]
    if failed_entries or failed_tests:
        print('\n== failed ==')
        for name in failed_entries:
            print('  ctest entry  %s' % name)
        for name in failed_tests:
            print('  test         %s' % name)
    return 0


if __name__ == '__main__':
    sys.exit(main())
