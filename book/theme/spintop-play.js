// spintop: ▶ runs a snippet through `spintop book`, the local server that
// compiles it against this spintop. mdBook's own button and output block
// (.play-button, .result) are kept; only where the code goes changes. The
// server writes a token into the pages it serves (window.spintopBook); a page
// without it (a static host, file://) gets a one-line explanation instead.
'use strict';

(function () {
    // The snippet whose ▶ was pressed last: its .result shows the progress
    // of a long (cold) run, which outlives mdBook's 6 s request.
    var current = null;
    document.addEventListener('click', function (e) {
        var button = e.target.closest && e.target.closest('.play-button');
        if (button) {
            current = button.closest('pre.playground');
        }
    }, true);

    function show(text) {
        var block = current && current.querySelector('.result');
        if (block) {
            block.innerText = text;
            block.classList.remove('result-no-output');
        }
    }

    // How long the status may go unanswered (503: the server could not
    // start a thread, as under a fork bomb; or no connection at all) before
    // the page gives up: the run itself goes on, bounded by its own limits.
    var PATIENCE_MS = 60000;

    function poll(token, started, failingSince) {
        setTimeout(function () {
            fetch('/evaluate/status', { headers: { 'X-Spintop-Token': token } })
                .then(function (r) {
                    if (r.status === 503) {
                        throw new Error('the server is busy (503)');
                    }
                    return r.json();
                })
                .then(function (s) {
                    if (s.done) {
                        show(s.result && s.result.trim() !== '' ? s.result : 'No output');
                    } else {
                        var secs = Math.round((Date.now() - started) / 1000);
                        var progress = s.progress || '';
                        if (progress === 'running') {
                            // Built: the snippet itself is running.
                            show('running… ' + secs + ' s');
                        } else if (progress.indexOf('background build') >= 0) {
                            show('compiling… ' + secs + ' s: ' + progress +
                                '\n(the first run builds spintop for the book; later runs take a second or two)');
                        } else {
                            show('compiling… ' + secs + ' s: ' + progress);
                        }
                        poll(token, started, null);
                    }
                }, function (err) {
                    // Busy or unreachable: not the run's result; ask again.
                    var since = failingSince || Date.now();
                    if (Date.now() - since > PATIENCE_MS) {
                        show('spintop book: no answer for ' + PATIENCE_MS / 1000 + ' s: ' + err.message);
                        return;
                    }
                    var secs = Math.round((Date.now() - started) / 1000);
                    show('waiting… ' + secs + ' s: ' + err.message + '; asking again');
                    poll(token, started, since);
                });
        }, 1000);
    }

    if (window.spintopBook && window.spintopBook.token) {
        var token = window.spintopBook.token;
        window.spintopRun = function (options) {
            var started = Date.now();
            return fetch('/evaluate.json', {
                method: 'POST',
                headers: { 'Content-Type': 'application/json', 'X-Spintop-Token': token },
                body: options.body,
            }).then(function (response) {
                if (response.status === 202) {
                    poll(token, started, null);
                }
                return response;
            });
        };
    }

    // mdBook shows ▶ once it has the playground's crate list; make sure it
    // is shown on every snippet that is not `no_run`.
    Array.from(document.querySelectorAll('pre.playground')).forEach(function (pre) {
        var code = pre.querySelector('code');
        var button = pre.querySelector('.play-button');
        if (button && code && !code.classList.contains('no_run')) {
            button.classList.remove('hidden');
            button.hidden = false;
        }
    });
})();
