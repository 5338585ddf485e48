"""The programs built on the codec. The codec (the package above) never imports them.

contract_tool.py  `nmea-py`, also `python -m nmeaspec`: NMEA lines to JSON and back, the JSON
                  the C and Rust tools print too, byte for byte (docs/json.md)
nmea_cli.py       `nmea`: a receiver log as a table, JSON lines or CSV; vendor commands built
                  and sent to a receiver, with its reply
report.py         `nmea report`: a receiver log as pictures in one HTML page (matplotlib)
export.py         `nmea export`: receiver logs as Parquet tables, fixes and sentences (pyarrow)
commands.py       the vendor commands `nmea command` builds, generated from the spec
"""
