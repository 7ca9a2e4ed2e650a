#pragma once
/// Suggestions for error messages: the known name closest to a mistyped one
/// ("unknown command 'optimze'; did you mean 'optimize'?", a bone name in a layout).
#include <string>
#include <vector>

namespace tightfit {

/// Levenshtein distance between `a` and `b` (insertions, deletions, substitutions).
int edit_distance(const std::string& a, const std::string& b);

/// The candidate closest to `word` by edit distance, when close enough to be a typo
/// (at most 2 edits, and fewer than half the word's length); empty otherwise.
std::string nearest_word(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace tightfit
