#pragma once
/// Escaping of text for XML and HTML documents (VTU files, SVG patterns, report.html).
#include <string>
#include <string_view>

namespace tightfit {

/// `text` with & < > " ' replaced by entity references (&amp; &lt; &gt; &quot; &#39;),
/// safe in element content and in quoted attribute values of XML 1.0 and HTML.
/// Control characters other than tab and newline (forbidden in XML 1.0) become spaces.
std::string xml_escape(std::string_view text);

/// Inverse of xml_escape for the five predefined entities (&apos; and &#39; both give
/// '\''); other '&' sequences are kept as they are.
std::string xml_unescape(std::string_view text);

}  // namespace tightfit
