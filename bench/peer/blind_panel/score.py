#!/usr/bin/env python3
"""score.py - tallies a blind panel's answers through its key.

    score.py KEY.tsv ANSWERS... [--words]

KEY.tsv is the key make_panel.sh wrote (outside the pairs folder); each
ANSWERS file is one judge's answers in the format of judge_brief.md:

    judge: NAME                              (optional; default the file's name)
    pair_03: water=A shape=B paper=A         (A, B, or = for no preference;
                                              ref=A|B|= too when the pairs show a reference)
    pair_03 A: glassy, clear, grainy edges   (words for each side, optional)

Prints, per judge and for all judges together, per comparison (the two
conditions a pair shows, e.g. "fc_floor vs vtk") and per question, how often
each condition was chosen and how often neither; with --words, the words
judges used for each condition. Exits 1 on an answer that does not parse, a
pair not in the key, or a pair a judge answered twice; a pair left unanswered
is listed, not counted.
Standard library only.
"""
import argparse
import os
import re
import sys
from collections import OrderedDict, defaultdict

PROG = "score"
QUESTIONS = ("water", "shape", "paper", "ref")
CHOICE = re.compile(r"^(pair_\d+)\s*:\s*(.*)$")
WORDS = re.compile(r"^(pair_\d+)\s+([AB])\s*:\s*(.*)$")


class ScoreError(Exception):
    pass


def read_key(path):
    """pair -> (condition A, condition B), and the seed."""
    pairs, seed = OrderedDict(), None
    with open(path) as f:
        for number, line in enumerate(f, 1):
            if line.startswith("#") or not line.strip():
                continue
            fields = line.rstrip("\n").split("\t")
            if fields[0] == "seed" and len(fields) >= 2:
                seed = fields[1]
            elif fields[0].startswith("pair_"):
                if len(fields) < 3:
                    raise ScoreError(f"{path}:{number}: a pair line needs PAIR<TAB>A<TAB>B")
                pairs[fields[0]] = (fields[1], fields[2])
    if not pairs:
        raise ScoreError(f"{path}: no pair lines: not a panel key")
    return pairs, seed


def read_answers(path, key):
    """(judge, {pair: {question: 'A'|'B'|'='}}, {pair: {side: words}})."""
    judge = os.path.splitext(os.path.basename(path))[0]
    choices, words = {}, defaultdict(dict)
    with open(path) as f:
        for number, raw in enumerate(f, 1):
            line = raw.strip().strip("`").strip()
            where = f"{path}:{number}"
            if not line or line.startswith("#"):
                continue
            if line.lower().startswith("judge:"):
                judge = line.split(":", 1)[1].strip() or judge
                continue
            m = WORDS.match(line)
            if m:
                check_pair(m.group(1), key, where)
                words[m.group(1)][m.group(2)] = m.group(3).strip()
                continue
            m = CHOICE.match(line)
            if not m:
                raise ScoreError(f"{where}: '{line}' is neither 'pair_NN: water=A ...' nor 'pair_NN A: words'")
            pair = m.group(1)
            check_pair(pair, key, where)
            if pair in choices:
                raise ScoreError(f"{where}: {pair} answered twice")
            choices[pair] = parse_choices(m.group(2), where)
    return judge, choices, words


def check_pair(pair, key, where):
    if pair not in key:
        raise ScoreError(f"{where}: {pair} is not in the key")


def parse_choices(text, where):
    answer = {}
    for item in text.replace(",", " ").split():
        question, _, value = item.partition("=")
        question, value = question.lower(), value.upper()
        if question not in QUESTIONS or value not in ("A", "B", "="):
            raise ScoreError(f"{where}: '{item}': want QUESTION=A|B|= with QUESTION one of {', '.join(QUESTIONS)}")
        if question in answer:
            raise ScoreError(f"{where}: {question} given twice")
        answer[question] = value
    if not answer:
        raise ScoreError(f"{where}: no answers")
    return answer


def comparison(sides):
    return " vs ".join(sorted(sides))


def tally(choices, key):
    """comparison -> question -> condition (or 'neither') -> count."""
    counts = defaultdict(lambda: defaultdict(lambda: defaultdict(int)))
    for pair, answer in choices.items():
        sides = key[pair]
        for question, value in answer.items():
            chosen = "neither" if value == "=" else sides[0 if value == "A" else 1]
            counts[comparison(sides)][question][chosen] += 1
    return counts


def print_tally(title, counts, out):
    print(f"== {title}", file=out)
    for comp in sorted(counts):
        conditions = sorted(comp.split(" vs ")) + ["neither"]
        print(f"  {comp}", file=out)
        for question in QUESTIONS:
            if question not in counts[comp]:
                continue
            row = counts[comp][question]
            cells = "  ".join(f"{c} {row.get(c, 0)}" for c in conditions)
            print(f"    {question:<6} {cells}   (of {sum(row.values())})", file=out)


def merge(into, counts):
    for comp, questions in counts.items():
        for question, row in questions.items():
            for condition, n in row.items():
                into[comp][question][condition] += n


def main(argv=None):
    p = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0],
                                epilog="Answer format: bench/peer/blind_panel/judge_brief.md")
    p.add_argument("key", help="the panel's key.tsv")
    p.add_argument("answers", nargs="+", help="one judge's answers per file")
    p.add_argument("--words", action="store_true", help="also list each condition's words")
    args = p.parse_args(argv)
    out = sys.stdout
    try:
        key, seed = read_key(args.key)
        total = defaultdict(lambda: defaultdict(lambda: defaultdict(int)))
        words_by_condition = defaultdict(list)
        print(f"panel {args.key}: {len(key)} pairs, seed {seed}", file=out)
        for path in args.answers:
            judge, choices, words = read_answers(path, key)
            missing = [pair for pair in key if pair not in choices]
            counts = tally(choices, key)
            print_tally(f"judge {judge} ({len(choices)} pairs answered)", counts, out)
            if missing:
                print(f"  unanswered: {' '.join(missing)}", file=out)
            merge(total, counts)
            for pair, sides in words.items():
                for side, text in sides.items():
                    words_by_condition[key[pair][0 if side == "A" else 1]].append(f"{text} ({judge}, {pair})")
        if len(args.answers) > 1:
            print_tally(f"all {len(args.answers)} judges", total, out)
        if args.words:
            print("== words", file=out)
            for condition in sorted(words_by_condition):
                print(f"  {condition}:", file=out)
                for text in words_by_condition[condition]:
                    print(f"    {text}", file=out)
    except (OSError, ScoreError) as e:
        print(f"{PROG}: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
